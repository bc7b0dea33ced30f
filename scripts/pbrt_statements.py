"""pbrt-v4's statements as its tokenizer splits them, for the scripts that rewrite scene files
(assemble_bitterli.py, pbrt_variant.py)."""
import re

TOKEN = re.compile(r'#[^\n]*|"[^"]*"|\[|\]|[^\s\[\]"#]+')


def statements(text):
    """(start, end, directive, tokens) of each statement, by pbrt-v4's lexical rules."""
    spans = []
    for m in TOKEN.finditer(text):
        tok = m.group(0)
        if tok.startswith("#"):
            continue
        if tok[0].isalpha() and tok[0].isupper():
            spans.append([m.start(), m.end(), tok, []])
        elif spans:
            spans[-1][1] = m.end()
            spans[-1][3].append(tok)
    return spans
