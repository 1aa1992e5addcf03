#!/usr/bin/env python3
"""Copy a pbrt-v4 scene with stand-ins for the files it names that are absent (bench/pbrt_corpus.sh, FORMAT v4-standins).

    python3 bench/pbrt_corpus_standins.py SCENE.pbrt OUT.pbrt

The snapshots the corpus was taken from lack every file of 4 MiB or more, so most of Bitterli's object scenes name
a mesh, an environment map or a texture that is not there, and neither renderer would load them. Both renderers
then read the same derived file, in which:

- a `Shape` whose `filename` is absent (a `plymesh`) is commented out;
- an `Import` or `Include` of an absent file is commented out;
- a `LightSource "infinite"` whose `filename` is absent becomes a uniform one, `"rgb L" [1 1 1]` (its other
  parameters, such as `scale`, and its transform kept);
- a `Texture ... "imagemap"` whose `filename` is absent becomes a `constant` texture of 0.5 (grey for a spectrum);
- a `measured` material whose `filename` (an RGL .bsdf file) is absent becomes `diffuse` with `rgb reflectance`
  0.5 (both renderers refuse a measured material without its file).

Five more rules make pbrt-v3 scenes (FORMAT v3-standins, upgraded first) readable by pbrt-v4 at all:

- a material of type `fourier` (pbrt-v3's tabulated BSDF, which the upgrader keeps and pbrt-v4 refuses) becomes
  `diffuse` with `rgb reflectance` 0.5, the stand-in Rimu itself uses for it;
- a `MakeNamedMedium` of type `heterogeneous` (pbrt-v3's density grid, which the upgrader means to rename but does
  not) becomes `uniformgrid`, which Rimu reads it as;
- a `Film`'s `maxcomponentvalue` (pbrt-v3's `maxsampleluminance`, upgraded) is removed: pbrt clamps each camera
  sample's largest sensor RGB component to it, a bias that depends on how each renderer samples wavelengths and
  paths (a uniform white sky of value 12 comes out 17 % darker under pbrt's clamp at 20, from the spread of its
  single-sample spectral estimates), so the two are compared unclamped (Rimu lists the parameter);
- an `infinite` light's `nsamples` (pbrt-v3's sample count, which the upgrader keeps and pbrt-v4 refuses as
  unused) is removed;
- with the environment variable PBRT_IMGTOOL naming pbrt-v4's `imgtool`, an `infinite` light's map that is not
  square (pbrt-v3's equirectangular maps, which pbrt-v4 refuses) is converted by `imgtool makeequiarea` to
  NAME.equiarea.exr next to it and the light reads that (pbrt-v4's own route for such maps). Rimu reads the
  original map itself (docs/pbrt-import.md); the corpus compares both on the converted one.

The comparison then covers what the scene still holds; what was replaced is printed, one line each, to stdout
(`standin: LINE: WHAT`), so that the summary can count it. The statement grammar used is pbrt-v4's: a statement is a
capitalised keyword followed by its quoted strings, numbers and bracketed lists; `#` starts a comment.
"""
import os
import re
import subprocess
import sys
from pathlib import Path

TOKEN = re.compile(r'"[^"]*"|\[|\]|#[^\n]*|[^\s\[\]"#]+')
KEYWORD = re.compile(r'[A-Z][A-Za-z]*$')


def statements(text):
    """(start, end, tokens) per statement; comments belong to no statement."""
    current = None
    for m in TOKEN.finditer(text):
        tok = m.group(0)
        if tok.startswith('#'):
            continue
        if KEYWORD.match(tok):
            if current:
                yield current
            current = [m.start(), m.end(), [tok]]
        elif current:
            current[1] = m.end()
            current[2].append(tok)
    if current:
        yield current


def parameter(tokens, type_name):
    """The first value of the parameter "type_name" (either spelling, with or without brackets), or None."""
    for i, tok in enumerate(tokens):
        if tok.startswith('"') and tok[1:-1].split() == type_name.split():
            j = i + 1
            if j < len(tokens) and tokens[j] == '[':
                j += 1
            return tokens[j].strip('"') if j < len(tokens) else None
    return None


def without_parameter(text, type_name):
    """The statement's text with the parameter "type_name" and its value removed."""
    words = r'\s+'.join(map(re.escape, type_name.split()))
    return re.sub(r'"\s*' + words + r'\s*"\s*(\[[^\]]*\]|"[^"]*")', '', text, count=1)


def image_is_square(imgtool, path):
    """Whether `imgtool info` reports a square image (True when it cannot tell)."""
    info = subprocess.run([imgtool, 'info', str(path)], capture_output=True, text=True).stdout
    m = re.search(r'resolution\s*\(?\s*(\d+)\s*,\s*(\d+)', info)
    return not m or m.group(1) == m.group(2)


def fourier_replacement(text):
    """A material statement's text (fourier, or measured without its file) as a grey diffuse one (its name kept, its
    parameters dropped)."""
    m = re.match(r'(MakeNamedMaterial\s+"[^"]*")', text)
    if m:
        return f'{m.group(1)} "string type" [ "diffuse" ] "rgb reflectance" [ 0.5 0.5 0.5 ]'
    return 'Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]'


def main(src, out):
    src = Path(src)
    text = src.read_text()
    base = src.parent
    pieces, last = [], 0
    for start, end, tokens in statements(text):
        keyword = tokens[0]
        line = text.count('\n', 0, start) + 1
        replacement = None
        if keyword in ('Import', 'Include') and len(tokens) > 1:
            name = tokens[1].strip('"')
            if not (base / name).is_file():
                replacement = f'# stand-in: {keyword} of absent {name} removed'
        elif keyword == 'Shape':
            name = parameter(tokens, 'string filename')
            if name and not (base / name).is_file():
                replacement = f'# stand-in: Shape {tokens[1]} of absent {name} removed'
        elif keyword == 'LightSource' and len(tokens) > 1 and tokens[1] == '"infinite"':
            name = parameter(tokens, 'string filename')
            imgtool = os.environ.get('PBRT_IMGTOOL')
            body, notes = text[start:end], []
            if parameter(tokens, 'integer nsamples') is not None:
                body = without_parameter(body, 'integer nsamples')
                notes.append("nsamples removed")
            if name and not (base / name).is_file():
                body = without_parameter(body, 'string filename') + '\n    "rgb L" [ 1 1 1 ]'
                notes.append(f'uniform, {name} absent')
            elif name and imgtool and not image_is_square(imgtool, base / name):
                converted = str(Path(name).with_suffix('')) + '.equiarea.exr'
                if not (base / converted).is_file():
                    subprocess.run([imgtool, 'makeequiarea', str(base / name), '--outfile', str(base / converted)],
                                   check=True, capture_output=True)
                body = without_parameter(body, 'string filename') + f'\n    "string filename" [ "{converted}" ]'
                notes.append(f'{name} made equal-area by imgtool makeequiarea')
            if notes:
                replacement = f'{body} # stand-in: {"; ".join(notes)}'
        elif keyword in ('Material', 'MakeNamedMaterial') and (
                (keyword == 'Material' and len(tokens) > 1 and tokens[1] == '"fourier"') or
                parameter(tokens, 'string type') == 'fourier'):
            replacement = f'{fourier_replacement(text[start:end])} # stand-in: fourier material as grey diffuse'
        elif keyword in ('Material', 'MakeNamedMaterial') and (
                (keyword == 'Material' and len(tokens) > 1 and tokens[1] == '"measured"') or
                parameter(tokens, 'string type') == 'measured'):
            name = parameter(tokens, 'string filename')
            if not name or not (base / name).is_file():
                replacement = (f'{fourier_replacement(text[start:end])} '
                               f'# stand-in: measured material as grey diffuse, {name} absent')
        elif keyword == 'Film' and parameter(tokens, 'float maxcomponentvalue') is not None:
            replacement = (f'{without_parameter(text[start:end], "float maxcomponentvalue")} '
                           f'# stand-in: maxcomponentvalue removed')
        elif keyword == 'MakeNamedMedium' and parameter(tokens, 'string type') == 'heterogeneous':
            body = re.sub(r'"heterogeneous"', '"uniformgrid"', text[start:end], count=1)
            replacement = f'{body} # stand-in: heterogeneous read as uniformgrid'
        elif keyword == 'Texture' and len(tokens) > 3 and tokens[3] == '"imagemap"':
            name = parameter(tokens, 'string filename')
            if name and not (base / name).is_file():
                value = '"rgb value" [ 0.5 0.5 0.5 ]' if tokens[2] == '"spectrum"' else '"float value" [ 0.5 ]'
                replacement = (f'Texture {tokens[1]} {tokens[2]} "constant" {value} '
                               f'# stand-in: constant, {name} absent')
        if replacement is not None:
            print(f'standin: {src.name}:{line}: {replacement.split("# stand-in: ")[1]}')
            pieces.append(text[last:start])
            pieces.append(replacement)
            last = end
    pieces.append(text[last:])
    Path(out).write_text(''.join(pieces))


if __name__ == '__main__':
    if len(sys.argv) != 3:
        sys.exit(f'usage: {sys.argv[0]} SCENE.pbrt OUT.pbrt')
    main(sys.argv[1], sys.argv[2])
