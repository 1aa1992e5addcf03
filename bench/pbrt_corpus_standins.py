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
- a `Texture ... "imagemap"` whose `filename` is absent becomes a `constant` texture of 0.5 (grey for a spectrum).

The comparison then covers what the scene still holds; what was replaced is printed, one line each, to stdout
(`standin: LINE: WHAT`), so that the summary can count it. The statement grammar used is pbrt-v4's: a statement is a
capitalised keyword followed by its quoted strings, numbers and bracketed lists; `#` starts a comment.
"""
import re
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
            if name and not (base / name).is_file():
                body = without_parameter(text[start:end], 'string filename')
                replacement = f'{body}\n    "rgb L" [ 1 1 1 ] # stand-in: uniform, {name} absent'
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
