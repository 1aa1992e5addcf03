#!/usr/bin/env python3
"""Fails when an #include in src/ runs back up between rooms.

The order is declared once, in docs/architecture.md, in the fenced block after the line "<!-- room order -->":
one line per library, bottom library first, each naming its rooms bottom first, e.g.

    spectral: (top-level) io wavelengths spectra ...
    render: film camera ... scene reports (top-level)

A library may include its own files and those of the libraries above it in the block; a room may include its own
files and those of the rooms before it on its line. A room is a folder right under the library's folder (its
sub-folders, e.g. render/scene/pbrt, belong to it); "(top-level)" stands for the files directly in the library's
folder. A file in a room the block does not declare fails too, so a new room gets its place in the order.

Usage: check_room_order.py [--doc docs/architecture.md] [--src src]   (paths relative to the repository root,
which is the working directory or the first positional argument).
"""
import argparse
import os
import re
import sys

TOP = "(top-level)"
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


def read_order(doc_path):
    """[(library, [room, ...]), ...] bottom first, from the block after '<!-- room order -->'."""
    with open(doc_path, encoding="utf-8") as doc:
        lines = doc.read().splitlines()
    try:
        start = lines.index("<!-- room order -->")
    except ValueError:
        sys.exit(f"{doc_path}: no '<!-- room order -->' line before the room order block")
    order, in_block = [], False
    for number, line in enumerate(lines[start + 1:], start + 2):
        if line.startswith("```"):
            if in_block:
                break
            in_block = True
            continue
        if not in_block or not line.strip():
            continue
        library, sep, rooms = line.partition(":")
        if not sep or not rooms.split():
            sys.exit(f"{doc_path}:{number}: expected 'library: room room ...', got '{line}'")
        order.append((library.strip(), rooms.split()))
    if not order:
        sys.exit(f"{doc_path}: the room order block after '<!-- room order -->' is empty")
    return order


def room_of(path):
    """(library, room) of a path relative to src/."""
    parts = path.split("/")
    return parts[0], (TOP if len(parts) == 2 else parts[1])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("root", nargs="?", default=".")
    parser.add_argument("--doc", default="docs/architecture.md")
    parser.add_argument("--src", default="src")
    args = parser.parse_args()
    doc = os.path.join(args.root, args.doc)
    src = os.path.join(args.root, args.src)
    order = read_order(doc)
    library_rank = {library: i for i, (library, _) in enumerate(order)}
    room_rank = {(library, room): i for library, rooms in order for i, room in enumerate(rooms)}

    problems = []
    for folder, _, files in sorted(os.walk(src)):
        for name in sorted(files):
            if not name.endswith((".h", ".cpp")):
                continue
            path = os.path.relpath(os.path.join(folder, name), src).replace(os.sep, "/")
            if "/" not in path:
                continue
            here = room_of(path)
            if here not in room_rank:
                problems.append(f"{args.src}/{path}: room {here[0]}/{here[1]} is not in the room order of {args.doc}")
                continue
            with open(os.path.join(folder, name), encoding="utf-8", errors="replace") as source:
                for number, line in enumerate(source, 1):
                    match = INCLUDE.match(line)
                    if not match or not os.path.isfile(os.path.join(src, match.group(1))):
                        continue  # a system header, a generated one, or one beside the file
                    there = room_of(match.group(1))
                    if there[0] != here[0]:
                        if library_rank.get(there[0], len(order)) > library_rank[here[0]]:
                            problems.append(f"{args.src}/{path}:{number}: includes {match.group(1)}: library "
                                            f"{there[0]} is above {here[0]} in the room order of {args.doc}")
                    elif room_rank.get(there, len(room_rank)) > room_rank[here]:
                        problems.append(f"{args.src}/{path}:{number}: includes {match.group(1)}: "
                                        f"{'/'.join(there)} is above {'/'.join(here)} in the room order of {args.doc}")
    for problem in problems:
        print(problem)
    if problems:
        print(f"{len(problems)} problem(s) with the room order: move the file or the declaration to the room that "
              f"owns it, or give a new room its place in {args.doc}")
        return 1
    print(f"room order holds: {sum(len(rooms) for _, rooms in order)} rooms in {len(order)} libraries")
    return 0


if __name__ == "__main__":
    sys.exit(main())
