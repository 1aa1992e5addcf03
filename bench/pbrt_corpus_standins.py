#!/usr/bin/env python3
"""Stand-ins for the files a corpus scene names but its snapshot lacks (bench/pbrt_corpus.txt, "-standins" rows).

    bench/pbrt_corpus_standins.py SCENE.pbrt [...]

Writes SCENE-standins.pbrt next to each SCENE.pbrt (pbrt-v4 syntax, one directive a line with its parameters on
the lines below, as the Bitterli files are written), with every statement that names a file that is not there
rewritten so that pbrt-v4 and Rimu both load the same, smaller scene:

- an image `Texture` becomes a `constant` one of value 0.5 (grey; the image's own mean is unknown);
- a `Shape` whose mesh file is missing is left out (commented);
- an `infinite` `LightSource` whose map is missing becomes a uniform one of `rgb L` [1 1 1] (its `scale` kept);
- an `Include` of a missing file is left out.

Each rewrite leaves a comment "# stand-in: ..." in place, and the script prints one line per rewrite. The result
is not the published scene: its rows compare the two renderers on the same input, not on the author's image.
(Files missing from this workplace's snapshots: those of 4 MiB and more, and the repository's .xz files, which
the scenes name without the .xz; a full clone, with the .xz files decompressed, needs no stand-ins.)
"""
import os
import re
import sys

FILENAME = re.compile(r'"string (filename|mapname)"\s*\[?\s*"([^"]*)"\s*\]?')
DIRECTIVE = re.compile(r'^\s*[A-Z][A-Za-z]*\b')


def statements(lines):
    """Groups lines into statements: a line that starts with a directive begins one."""
    current = []
    for line in lines:
        if DIRECTIVE.match(line) and current:
            yield current
            current = []
        current.append(line)
    if current:
        yield current


def missing_files(statement, folder):
    # Only the inputs: a Film's filename is an output.
    if not re.match(r'^\s*(Texture|Shape|LightSource|Include|Import)\b', statement[0]):
        return []
    names = []
    for line in statement:
        if line.lstrip().startswith('#'):
            continue
        for m in FILENAME.finditer(line):
            names.append(m.group(2))
        inc = re.match(r'^\s*(Include|Import)\s+"([^"]*)"', line)
        if inc:
            names.append(inc.group(2))
    return [n for n in names if not os.path.isfile(os.path.join(folder, n))]


def rewrite(statement, missing):
    head = statement[0]
    indent = re.match(r'^(\s*)', head).group(1)
    note = f'{indent}# stand-in: {", ".join(missing)} missing\n'
    tex = re.match(r'^(\s*Texture\s+"[^"]*"\s+"(spectrum|float)")\s+"imagemap"', head)
    if tex:
        value = '"float value" 0.5' if tex.group(2) == 'float' else '"rgb value" [ 0.5 0.5 0.5 ]'
        return [note, f'{tex.group(1)} "constant" {value}\n'], 'image texture -> constant 0.5'
    if re.match(r'^\s*LightSource\s+"infinite"', head):
        kept = [l for l in statement[1:] if not FILENAME.search(l)]
        return [note, head, f'{indent}    "rgb L" [ 1 1 1 ]\n'] + kept, 'infinite light map -> uniform rgb L 1'
    if re.match(r'^\s*(Shape|Include|Import)\b', head):
        return [note] + ['# ' + l for l in statement], 'left out'
    raise SystemExit(f'{head.strip()}: no stand-in for a missing {missing}')


def main():
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    for path in sys.argv[1:]:
        folder = os.path.dirname(os.path.abspath(path))
        with open(path) as f:
            lines = f.readlines()
        out = []
        for statement in statements(lines):
            missing = missing_files(statement, folder)
            if missing:
                replaced, what = rewrite(statement, missing)
                print(f'{path}: {statement[0].strip()[:60]} ({", ".join(missing)}): {what}')
                out.extend(replaced)
            else:
                out.extend(statement)
        target = os.path.splitext(path)[0] + '-standins.pbrt'
        with open(target, 'w') as f:
            f.writelines(out)


if __name__ == '__main__':
    main()
