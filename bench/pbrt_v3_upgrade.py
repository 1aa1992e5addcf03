#!/usr/bin/env python3
"""Upgrade a pbrt-v3 scene and every file it Includes with pbrt-v4's upgrader (bench/pbrt_corpus.sh, FORMAT v3).

    python3 bench/pbrt_v3_upgrade.py PBRT_BINARY SCENE.pbrt OUT.pbrt

`pbrt --upgrade FILE` rewrites FILE's own statements but prints each `Include "x"` as it is, so an included
pbrt-v3 file (most pbrt-v3 scenes keep their materials and geometry in `materials.pbrt` and `geometry.pbrt`) stays
pbrt-v3 and pbrt-v4 then stops at its first v3 parameter. pbrt-v3's `Include` is textual (the included tokens
continue the including file's token stream: pbrt-v3-scenes' cloud.pbrt begins a statement in one file and gives
its parameters in the other), so this script first writes one file with every `Include` replaced by the text it
names (recursively; names relative to the scene's folder, as pbrt resolves them), then runs the upgrader once on
it. OUT is written next to SCENE's folder-relative names, so OUT must be in SCENE's folder. `Import` (pbrt-v4
only) is left alone. Exit status: the upgrader's; its messages go to stderr.
"""
import re
import subprocess
import sys
from pathlib import Path

TOKEN = re.compile(r'"[^"]*"|#[^\n]*|[^\s"#]+')


def inline(path: Path, base: Path, depth: int = 0) -> str:
    if depth > 32:
        sys.exit(f"{path}: Include nested more than 32 deep")
    text = path.read_text(errors='replace')
    out = []
    last = 0
    tokens = list(TOKEN.finditer(text))
    i = 0
    while i < len(tokens):
        tok = tokens[i].group(0)
        if tok == 'Include' and i + 1 < len(tokens) and tokens[i + 1].group(0).startswith('"'):
            name = tokens[i + 1].group(0)[1:-1]
            target = Path(name) if Path(name).is_absolute() else base / name
            if not target.is_file():  # left as it is: bench/pbrt_corpus_standins.py removes it, or pbrt reports it
                i += 2
                continue
            out.append(text[last:tokens[i].start()])
            out.append(f'\n# ---- Include "{name}" (inlined by pbrt_v3_upgrade.py)\n')
            out.append(inline(target, base, depth + 1))
            out.append(f'\n# ---- end of "{name}"\n')
            last = tokens[i + 1].end()
            i += 2
            continue
        i += 1
    out.append(text[last:])
    return ''.join(out)


def main() -> int:
    if len(sys.argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    pbrt, scene, out = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
    base = scene.resolve().parent
    if out.resolve().parent != base:
        sys.exit(f"{out}: must be in the scene's folder {base} (the scene's file names are relative to it)")
    flat = out.with_name(out.stem + '.inlined.pbrt')
    flat.write_text(inline(scene, base))
    with open(out, 'w') as f:
        status = subprocess.run([pbrt, '--upgrade', str(flat)], stdout=f).returncode
    flat.unlink()
    return status


if __name__ == '__main__':
    sys.exit(main())
