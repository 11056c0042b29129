#!/usr/bin/env python3
"""Every relative link of the repository's documents points into the repository, and no file cites a folder outside it.

Checks every tracked Markdown file (git ls-files; outside a git checkout, every file but hidden and build
folders): each relative link or image, inline `[text](target)` or a
reference definition `[label]: target`, must name a file or folder of the repository, and its `#anchor` (also an
anchor alone, within the page) a heading of that Markdown file (GitHub's rule: lower case, punctuation dropped,
spaces to '-', '-1', '-2' for repeats). Also the `#:schema PATH` lines of the scenes (scenes/*.toml) must name a
file. Finally no tracked text file (documents, sources, CMake, scripts) may mention the developers' folder beside the
repository (OUTSIDE below), which users do not have. Links to http(s) and mailto are not followed. Code spans and fenced
code blocks are not links.

Every problem is listed, one line each (FILE:LINE: what), then the exit status is 1; 0 when there is none.

Usage (ctest runs it, label unit): check_links.py REPOSITORY_ROOT
"""
import os
import re
import subprocess
import sys
import urllib.parse

INLINE = re.compile(r'!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]*)>?(?:\s+"[^"]*")?\s*\)')
REFERENCE = re.compile(r'^ {0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+.*)?$')
SCHEMA = re.compile(r'^#:schema\s+(\S+)')


# The folder outside the repository that no file may name (written in two parts, so that this file does not).
OUTSIDE = '../' + 'shared'


def tracked_files(root):
    """git's tracked files; outside a git checkout (a source archive, an install's share/crankcheck), every file but
    hidden and build folders."""
    try:
        out = subprocess.run(['git', '-C', root, 'ls-files', '-z'], check=True, capture_output=True).stdout
        names = [name for name in out.decode('utf-8').split('\0') if name]
        if names:
            return names
        raise OSError('no tracked file: an install tree or an untracked folder of a checkout')
    except (OSError, subprocess.CalledProcessError):
        names = []
        for folder, dirs, files in os.walk(root):
            dirs[:] = [d for d in dirs if not d.startswith('.') and not d.startswith(('build', 'out'))]
            names += [os.path.relpath(os.path.join(folder, f), root) for f in files]
        return sorted(names)


def slug(heading):
    text = re.sub(r'`([^`]*)`', r'\1', heading.strip())
    text = re.sub(r'!?\[([^\]]*)\]\([^)]*\)', r'\1', text)  # a link in a heading keeps its text
    text = text.lower()
    text = re.sub(r'[^\w\- ]', '', text)
    return text.replace(' ', '-')


def outside_fences(lines):
    """Each line, or None for the lines of fenced code blocks (``` or ~~~) and their fences."""
    fence = None
    for line in lines:
        stripped = line.lstrip()
        marker = re.match(r'(`{3,}|~{3,})', stripped)
        if fence:
            if marker and stripped.startswith(fence):
                fence = None
            yield None
        elif marker:
            fence = marker.group(1)
            yield None
        else:
            yield line


def strip_code(lines):
    """The lines with fenced blocks blanked and code spans removed (links inside code are not links)."""
    return ['' if line is None else re.sub(r'(`+)(?:(?!\1).)*?\1', '', line) for line in outside_fences(lines)]


def anchors_of(path, cache):
    if path not in cache:
        seen, found = {}, set()
        with open(path, encoding='utf-8') as f:
            text = f.read().split('\n')
        for line in outside_fences(text):
            if line is None:
                continue
            m = re.match(r'^ {0,3}#{1,6}\s+(.*?)\s*#*\s*$', line)
            if m:
                base = slug(m.group(1))
                n = seen.get(base, 0)
                seen[base] = n + 1
                found.add(base if n == 0 else f'{base}-{n}')
            for a in re.findall(r'<a\s+(?:name|id)="([^"]+)"', line):
                found.add(a)
        cache[path] = found
    return cache[path]


def check_target(root, source, lineno, target, problems, cache):
    if not target or re.match(r'^[a-zA-Z][a-zA-Z0-9+.-]*:', target):  # http:, https:, mailto:, ...
        return
    path_part, _, anchor = target.partition('#')
    path_part = urllib.parse.unquote(path_part)
    if path_part.startswith('/'):
        problems.append(f'{source}:{lineno}: absolute link {target!r}: links must be relative to the file')
        return
    base = os.path.dirname(os.path.join(root, source))
    full = os.path.normpath(os.path.join(base, path_part)) if path_part else os.path.join(root, source)
    if os.path.relpath(full, root).startswith('..'):
        problems.append(f'{source}:{lineno}: link {target!r} leaves the repository')
        return
    if not os.path.exists(full):
        problems.append(f'{source}:{lineno}: link {target!r}: no such file in the repository')
        return
    if anchor and full.endswith('.md') and os.path.isfile(full):
        if anchor not in anchors_of(full, cache):
            problems.append(f'{source}:{lineno}: link {target!r}: no heading #{anchor} in '
                            f'{os.path.relpath(full, root)}')


def main(argv):
    if len(argv) != 2 or argv[1] in ('-h', '--help'):
        print(__doc__.strip().split('\n\n')[-1], file=sys.stderr)
        return 2
    root = os.path.abspath(argv[1])
    files = tracked_files(root)
    problems, cache, markdown = [], {}, 0
    for name in files:
        path = os.path.join(root, name)
        if not os.path.isfile(path):
            continue
        # No tracked text file at all (documents, sources, CMake, scripts) names the folder outside the repository.
        try:
            with open(path, encoding='utf-8') as f:
                lines = f.read().split('\n')
        except UnicodeDecodeError:
            continue  # not text
        for i, line in enumerate(lines, 1):
            if OUTSIDE in line:
                problems.append(f'{name}:{i}: mentions {OUTSIDE}, a folder outside the repository')
        is_doc = name.endswith('.md') or (name.startswith('scenes/') and name.endswith('.toml')) \
            or name == 'docs/scene.schema.json'
        if not is_doc:
            continue
        if name.endswith('.md'):
            markdown += 1
            for i, line in enumerate(strip_code(lines), 1):
                for target in INLINE.findall(line):
                    check_target(root, name, i, target, problems, cache)
                m = REFERENCE.match(line)
                if m:
                    check_target(root, name, i, m.group(1), problems, cache)
        elif name.endswith('.toml'):
            for i, line in enumerate(lines, 1):
                m = SCHEMA.match(line)
                if m:
                    check_target(root, name, i, m.group(1), problems, cache)
    for p in problems:
        print(p)
    if markdown == 0:
        print(f'{root}: no tracked Markdown file found: the repository was not read')
        return 1
    if problems:
        print(f'{len(problems)} broken link(s) or mention(s) of {OUTSIDE} in {markdown} Markdown files and the scenes')
        return 1
    print(f'{markdown} Markdown files and the scenes: every relative link resolves; no file mentions {OUTSIDE}')
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
