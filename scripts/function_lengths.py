#!/usr/bin/python3
"""Lists the long functions of C++ and OpenCL C sources.

Usage: python3 scripts/function_lengths.py [--over N] [--top K] PATH...
  PATH     files or folders (folders are searched for .cpp, .h and .cl files)
  --over N list the functions longer than N lines (default 100; 0 with --top alone)
  --top K  list only the K longest of those

Prints one line per function, longest first: LINES path:line name. Always exits 0.

A function is an outermost {...} (at namespace or class scope) whose header, the text since the
previous ';', '}' or '{' at that depth, holds a parameter list (...) followed only by qualifiers,
a trailing return type or a constructor's initializer list. Namespaces, classes, structs, unions
and extern "C" blocks are searched inside; enums and braced data are not functions. Lambdas and
local classes count as part of the function around them. Its length counts the lines from the
header's first line to the closing brace, both included. Comments, string and character literals
and preprocessor lines are blanked first. A heuristic: it knows no types, only the text's shape.
Python 3 standard library only.
"""
import argparse
import os
import re
import sys

EXTENSIONS = (".cpp", ".h", ".cl")
CONTROL = {"if", "for", "while", "switch", "catch", "return", "sizeof", "do", "else"}
TEST_MACROS = {"TEST", "TEST_F", "TEST_P", "TYPED_TEST", "TYPED_TEST_P"}
# What may follow a function's parameter list before its body, once every (...) in it reads "()".
TAIL = re.compile(
    r"^(?:\s|const\b|volatile\b|noexcept\b|override\b|final\b|mutable\b|try\b|throw\b|&|\(\)"
    r"|\[\[[^\]]*\]\]|->.*|:(?!:).*)*$",
    re.S,
)
NAME = re.compile(r"((?:[A-Za-z_]\w*\s*(?:<[^<>;{}]*>)?\s*::\s*)*~?[A-Za-z_]\w*)\s*$")
OPERATOR = re.compile(r"((?:[A-Za-z_]\w*\s*::\s*)*operator\s*(?:\(\)|[^\s(]+|\s+[\w:<>*&\s]+?))\s*$")


def blank(text):
    """The text with comments, literals and preprocessor lines replaced by spaces, newlines kept."""
    out = []
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c == "#":
            j = i
            while j < n and text[j] != "\n":
                j = j + 2 if text[j] == "\\" and j + 1 < n else j + 1
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
            continue
        if c == "\n":
            line_start = True
            out.append(c)
            i += 1
            continue
        if not c.isspace():
            line_start = False
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == '"' or (c == "'" and not is_digit_separator(text, i)):
            j = literal_end(text, i)
            out.append(c + re.sub(r"[^\n]", " ", text[i + 1 : j - 1]) + c)
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def is_digit_separator(text, i):
    """Whether the ' at i separates digits (1'000) rather than opening a character literal."""
    m = re.search(r"(\w+)$", text[max(0, i - 64) : i])
    return bool(m) and m.group(1)[0].isdigit()


def literal_end(text, i):
    """The index just past the string or character literal that opens at i."""
    quote = text[i]
    raw = re.search(r"(?:\b|^)(?:u8|u|U|L)?R$", text[max(0, i - 3) : i])
    if quote == '"' and raw:
        m = re.match(r'"([^()\\\s]{0,16})\(', text[i:])
        if m:
            close = text.find(")" + m.group(1) + '"', i + m.end())
            return len(text) if close < 0 else close + len(m.group(1)) + 2
    j = i + 1
    while j < len(text) and text[j] != quote and text[j] != "\n":
        j += 2 if text[j] == "\\" else 1
    return min(j + 1, len(text))


def matching(text, i, open_c, close_c):
    """The index of the bracket that closes the one at i."""
    depth = 0
    for j in range(i, len(text)):
        if text[j] == open_c:
            depth += 1
        elif text[j] == close_c:
            depth -= 1
            if depth == 0:
                return j
    return len(text) - 1


def top_level_groups(header):
    """The (start, end) of each (...) group of the header that is outside any other bracket."""
    groups, depth, start = [], 0, 0
    for j, c in enumerate(header):
        if c == "(":
            if depth == 0:
                start = j
            depth += 1
        elif c == ")" and depth > 0:
            depth -= 1
            if depth == 0:
                groups.append((start, j))
    return groups


def collapse_groups(text):
    """The text with each outermost (...) group written as ()."""
    out, depth = [], 0
    for c in text:
        if c == "(":
            if depth == 0:
                out.append("()")
            depth += 1
        elif c == ")" and depth > 0:
            depth -= 1
        elif depth == 0:
            out.append(c)
    return "".join(out)


def function_name(header):
    """The function's name if the header is a function's, else None."""
    if re.search(r"=\s*$", header):
        return None
    for start, end in top_level_groups(header):
        prefix = header[:start]
        if re.search(r"\boperator\s*$", prefix):
            continue  # operator()'s own parentheses
        if not TAIL.match(collapse_groups(header[end + 1 :])):
            continue
        if top_level_equals(prefix):
            lam = re.search(r"([A-Za-z_]\w*)\s*=\s*\[[^\]]*\]\s*$", prefix)
            return lam.group(1) if lam else None
        m = OPERATOR.search(prefix) or NAME.search(prefix)
        if not m:
            return None
        name = re.sub(r"\s+", "", m.group(1)) if "operator" not in m.group(1) else m.group(1)
        if name.split("::")[-1] in CONTROL:
            return None
        if name in TEST_MACROS:  # name a test by its suite and test
            name += re.sub(r"\s+", " ", header[start : end + 1])
        return name
    return None


def top_level_equals(prefix):
    """Whether the prefix holds an '=' outside brackets that is not part of an operator name."""
    depth = 0
    for j, c in enumerate(prefix):
        if c in "(<[":
            depth += 1
        elif c in ")>]":
            depth = max(0, depth - 1)
        elif c == "=" and depth == 0:
            before, after = prefix[max(0, j - 1)], prefix[j + 1 : j + 2]
            if before not in "=!<>+-*/%&|^" and after != "=":
                if not re.search(r"\boperator\s*$", prefix[:j]):
                    return True
    return False


def container_name(header):
    """'namespace', the class's name for a class, struct or union, or None for anything else."""
    h = header.strip()
    if re.match(r"^(?:inline\s+)?namespace\b", h) or re.match(r'^extern\s*"', h):
        return "namespace"
    h = re.sub(r"^template\s*<.*?>\s*", "", h, flags=re.S)
    m = re.match(r"^(?:typedef\s+)?(?:class|struct|union)\b\s*(?:\[\[[^\]]*\]\]\s*)?(\w*)", h)
    if m and not re.match(r"^\s*enum\b", h):
        return m.group(1) or "namespace"
    return None


def in_initializer_list(header):
    """Whether the header ends inside a constructor's member initializer list."""
    groups = top_level_groups(header)
    for start, end in groups:
        if re.match(r"^\s*(?:noexcept\s*(?:\(\))?\s*)?:(?!:)", collapse_groups(header[end + 1 :])):
            return True
    return False


def functions(text):
    """Yields (first line, last line, name) for each function of the source text."""
    code = blank(text)
    line_of = []
    line = 1
    for c in code:
        line_of.append(line)
        if c == "\n":
            line += 1
    yield from scan(code, 0, len(code), line_of, "")


def scan(code, begin, end, line_of, scope):
    """Yields the functions in code[begin:end], a namespace or class body."""
    header_start = begin
    i = begin
    while i < end:
        c = code[i]
        if c == ";" or c == "}":
            header_start = i + 1
        elif c == ":" and re.search(r"\b(?:public|private|protected)\s*$", code[header_start:i]):
            header_start = i + 1
        elif c == "(":
            i = matching(code, i, "(", ")")
        elif c == "{":
            header = code[header_start:i]
            close = matching(code, i, "{", "}")
            if in_initializer_list(header) and re.search(r"(?:\w|>|\.\.\.)\s*$", header):
                i = close + 1  # a member's braced initializer: still the header
                continue
            kind = container_name(header)
            name = function_name(header) if kind is None else None
            if kind == "namespace":
                yield from scan(code, i + 1, close, line_of, scope)
            elif kind is not None:
                yield from scan(code, i + 1, close, line_of, scope + kind + "::")
            elif name is not None:
                first = header_start + len(header) - len(header.lstrip())
                qualified = name if "::" in name else scope + name
                yield line_of[first], line_of[close], qualified
            header_start = close + 1
            i = close
        i += 1


def source_files(paths):
    for path in paths:
        if os.path.isdir(path):
            for root, dirs, files in os.walk(path):
                dirs.sort()
                for f in sorted(files):
                    if f.endswith(EXTENSIONS):
                        yield os.path.join(root, f)
        else:
            yield path


def main():
    parser = argparse.ArgumentParser(description="Lists the long functions of C++/OpenCL sources.")
    parser.add_argument("paths", nargs="+")
    parser.add_argument("--over", type=int, default=None, help="list functions longer than N lines")
    parser.add_argument("--top", type=int, default=None, help="list the K longest")
    args = parser.parse_args()
    over = args.over if args.over is not None else (0 if args.top is not None else 100)
    rows = []
    for path in source_files(args.paths):
        try:
            with open(path, encoding="utf-8", errors="replace") as f:
                text = f.read()
        except OSError as e:
            print(f"{path}: {e.strerror}", file=sys.stderr)
            continue
        for first, last, name in functions(text):
            length = last - first + 1
            if length > over:
                rows.append((length, path, first, name))
    rows.sort(key=lambda r: (-r[0], r[1], r[2]))
    if args.top is not None:
        rows = rows[: args.top]
    for length, path, first, name in rows:
        print(f"{length} {path}:{first} {name}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
