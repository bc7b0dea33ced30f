#!/usr/bin/python3
"""Checks that kasha's documentation links resolve.

Usage: python3 scripts/check_links.py [ROOT]   (ROOT: the source tree, default: this script's ..)

1. Every relative link and image (Markdown, or HTML <a href> and <img src>) in README.md and in
   the Markdown files under docs/ names an existing file or folder, and every #anchor in such a
   link (to a Markdown file, or #anchor alone for the same file) is the slug of one of the
   target's headings, as GitHub makes them: lowercase; letters of any script, digits, '-' and
   '_' kept; spaces to '-'; other punctuation dropped; repeated headings numbered -1, -2, ...
2. Every pointer into the Markdown docs from the code (a path such as docs/design.md or
   docs/formats.md#scenes in a comment of a file under host/, kernels/, tests/ or scripts/)
   resolves the same way, relative to ROOT.

Prints one line per broken link, FILE:LINE: broken link TARGET, and exits 1 if there is one;
exits 0 when every link resolves. Python 3 standard library only (CI runs Debian's python3).
"""
import os
import re
import sys
import unicodedata
from urllib.parse import unquote

CODE_DIRS = ("host", "kernels", "tests", "scripts")

FENCE = re.compile(r"^ {0,3}(`{3,}|~{3,})")
ATX_HEADING = re.compile(r"^ {0,3}(#{1,6})(?:[ \t]+(.*?))?(?:[ \t]+#+)?[ \t]*$")
SETEXT_UNDERLINE = re.compile(r"^ {0,3}(=+|-+)[ \t]*$")
HTML_ANCHOR = re.compile(r"""<a\s[^>]*?(?:name|id)\s*=\s*["']([^"']+)["']""", re.IGNORECASE)
CODE_SPAN = re.compile(r"(`+)(.+?)\1")
# [text](target "title") and ![alt](target); the target may be in <angle brackets>.
INLINE_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*(<[^>]*>|[^\s()]*(?:\([^\s()]*\)[^\s()]*)*)")
HTML_LINK = re.compile(r"""<(?:a|img)\s[^>]*?(?:href|src)\s*=\s*["']([^"']*)["']""", re.IGNORECASE)
REFERENCE_DEFINITION = re.compile(r"^ {0,3}\[[^\]]+\]:\s*(<[^>]*>|\S+)")
# A pointer into the docs from the code: a path under docs/ ending in .md, with an optional
# #anchor; any folder depth. Resolved against ROOT.
CODE_POINTER = re.compile(r"(?<![A-Za-z0-9_-])(docs/[A-Za-z0-9_./-]*?\.md)(#[A-Za-z0-9_-]+)?(?![A-Za-z0-9_])")
EXTERNAL = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")  # http:, https:, mailto:, …


def slug(text):
    """GitHub's anchor for a heading's text (github-slugger): lowercase; letters (any script),
    digits, marks, '-' and '_' kept, spaces to '-', everything else dropped."""
    out = []
    for ch in text.strip().lower():
        if ch == " ":
            out.append("-")
        elif ch in "-_" or unicodedata.category(ch)[0] in "LNM":
            out.append(ch)
    return "".join(out)


def heading_text(raw):
    """The text GitHub renders for a heading's Markdown: code spans keep their content, links
    their text, HTML tags and emphasis markers go."""
    parts = []
    pos = 0
    for m in CODE_SPAN.finditer(raw):
        parts.append(("text", raw[pos:m.start()]))
        parts.append(("code", m.group(2).strip() if m.group(2).strip() else m.group(2)))
        pos = m.end()
    parts.append(("text", raw[pos:]))
    text = []
    for kind, s in parts:
        if kind == "text":
            s = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", s)  # links and images: their text
            s = re.sub(r"<[^>]+>", "", s)  # HTML tags
            s = s.replace("*", "")
            s = re.sub(r"(?<![A-Za-z0-9])_+|_+(?![A-Za-z0-9])", "", s)  # _emphasis_, not snake_case
            s = s.replace("\\", "")
        text.append(s)
    return "".join(text)


def markdown_lines(text):
    """(line number, line) of the lines outside fenced code blocks."""
    fence = None
    for number, line in enumerate(text.splitlines(), 1):
        m = FENCE.match(line)
        if fence:
            if m and m.group(1)[0] == fence[0] and len(m.group(1)) >= len(fence):
                fence = None
            continue
        if m:
            fence = m.group(1)
            continue
        yield number, line


_anchor_cache = {}


def anchors_of(path):
    """The anchors of a Markdown file: its headings' slugs (duplicates numbered -1, -2, …) and
    explicit <a name|id> anchors."""
    if path in _anchor_cache:
        return _anchor_cache[path]
    with open(path, encoding="utf-8", errors="replace") as f:
        lines = list(markdown_lines(f.read()))
    seen = {}
    anchors = set()

    def add(raw):
        base = slug(heading_text(raw))
        n = seen.get(base, 0)
        anchors.add(base if n == 0 else "%s-%d" % (base, n))
        seen[base] = n + 1

    previous = None  # the previous line, if it could be a setext heading's text
    previous_number = None
    for number, line in lines:
        for m in HTML_ANCHOR.finditer(line):
            anchors.add(m.group(1))
        m = ATX_HEADING.match(line)
        if m:
            add(m.group(2) or "")
            previous = None
            continue
        if (previous is not None and previous_number == number - 1
                and SETEXT_UNDERLINE.match(line) and previous.strip()
                and not previous.startswith(("    ", "\t", ">", "-", "*", "|"))):
            add(previous.strip())
            previous = None
            continue
        previous, previous_number = line, number
    _anchor_cache[path] = anchors
    return anchors


def resolve(root, source_dir, target):
    """None when `target` (a relative link from a file in source_dir) resolves, else why not."""
    path_part, _, anchor = target.partition("#")
    path_part = unquote(path_part)
    anchor = unquote(anchor)
    if path_part:
        if path_part.startswith("/"):
            full = os.path.join(root, path_part.lstrip("/"))
        else:
            full = os.path.join(source_dir, path_part)
        full = os.path.normpath(full)
        if not os.path.exists(full):
            return "no such file"
    else:
        full = None
    if anchor and (full is None or full.endswith(".md")):
        if full is None:
            return "no target"  # the caller passes the source file for a bare #anchor
        if os.path.isdir(full) or anchor not in anchors_of(full):
            return "no such heading"
    return None


def markdown_files(root):
    files = []
    readme = os.path.join(root, "README.md")
    if os.path.isfile(readme):
        files.append(readme)
    for directory, subdirs, names in os.walk(os.path.join(root, "docs")):
        subdirs.sort()
        for name in sorted(names):
            if name.endswith(".md"):
                files.append(os.path.join(directory, name))
    return files


def check_markdown(root, path, report):
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    for number, line in markdown_lines(text):
        targets = []
        m = REFERENCE_DEFINITION.match(line)
        if m:
            targets.append(m.group(1))
        without_code = CODE_SPAN.sub(lambda c: " " * len(c.group(0)), line)
        targets += [m.group(1) for m in INLINE_LINK.finditer(without_code)]
        targets += [m.group(1) for m in HTML_LINK.finditer(without_code)]
        for target in targets:
            if target.startswith("<") and target.endswith(">"):
                target = target[1:-1]
            if not target or EXTERNAL.match(target):
                continue
            if target.startswith("#"):
                ok = target[1:] == "" or unquote(target[1:]) in anchors_of(path)
            else:
                ok = resolve(root, os.path.dirname(path), target) is None
            if not ok:
                report(path, number, target)


def check_code(root, report):
    for top in CODE_DIRS:
        for directory, subdirs, names in os.walk(os.path.join(root, top)):
            subdirs.sort()
            for name in sorted(names):
                path = os.path.join(directory, name)
                try:
                    with open(path, "rb") as f:
                        data = f.read()
                except OSError:
                    continue
                if b"\0" in data:
                    continue  # binary
                text = data.decode("utf-8", errors="replace")
                for number, line in enumerate(text.splitlines(), 1):
                    for m in CODE_POINTER.finditer(line):
                        target = m.group(1) + (m.group(2) or "")
                        if resolve(root, root, target) is not None:
                            report(path, number, target)


def main(argv):
    root = os.path.abspath(argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    broken = []

    def report(path, number, target):
        broken.append("%s:%d: broken link %s" % (os.path.relpath(path, root), number, target))

    for path in markdown_files(root):
        check_markdown(root, path, report)
    check_code(root, report)
    for line in broken:
        print(line)
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
