#!/usr/bin/env python3
"""Lists C++ functions whose bodies are longer than a limit; exits 1 if there are any.

    python3 tools/dev/function_length.py [--limit 80] [PATH ...]      (default: src)

A function is a brace block whose head (the text since the previous ';', '{' or
'}') ends in a parameter list, optionally followed by qualifiers, a trailing
return type or a constructor's initialiser list, and which is not nested in
another function (lambdas and local classes count towards their enclosing
function). Comments and string literals are ignored. Length counts the lines
from the opening to the closing brace, both included. It is a heuristic
matcher, not a parser: it is exact for this codebase's style (checked against
the functions the issue-13 review measured) and errs towards reporting.
"""
import argparse
import os
import re
import sys

KEYWORDS = {"if", "for", "while", "switch", "catch", "return", "sizeof", "decltype", "alignof", "noexcept"}
FUNCTION_HEAD = re.compile(r"([~\w:<>=!+\-*/&|\[\]]+)\s*\([^;]*\)\s*((const|noexcept|override|final|->[^{]*)\s*)*$")
TYPE_HEAD = re.compile(r"^(template\s*<.*>\s*)?(namespace|class|struct|enum|union)\b")


def strip_comments_and_literals(text):
    """The text with comments removed and literals emptied; newlines are kept."""
    out, i, n = [], 0, len(text)
    while i < n:
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
            continue
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
            continue
        raw = re.match(r'R"([^(]*)\(', text[i:i + 20])
        if raw:
            end = ")" + raw.group(1) + '"'
            j = text.find(end, i)
            j = n if j < 0 else j + len(end)
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j
            continue
        c = text[i]
        if c in "\"'" and not (c == "'" and i > 0 and text[i - 1].isalnum()):  # 1'000 digit separators
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
            continue
        out.append(c)
        i += 1
    return "".join(out)


def function_name(head):
    """The function's name if a block with this head is a function body, else None."""
    head = " ".join(head.split())
    if TYPE_HEAD.match(head):
        return None
    m = re.search(r"\)\s*:\s*[\w:]+\s*[({]", head)  # constructor initialiser list
    if m:
        head = head[:m.start() + 1]
    m = FUNCTION_HEAD.search(head)
    if not m:
        return None
    name = m.group(1)
    if name.split("::")[-1] in KEYWORDS:
        return None
    before_paren = head.split("(")[0].replace("operator==", "").replace("operator=", "").replace("==", "")
    if "=" in before_paren:  # an initialiser, e.g. `auto f = [](...) {`
        return None
    return name


def functions(text):
    """(name, first line, last line) of every outermost function body."""
    s = strip_comments_and_literals(text)
    stack, found, line, head_start = [], [], 1, 0
    for i, c in enumerate(s):
        if c == "\n":
            line += 1
        elif c == "{":
            inside_function = any(kind == "fn" for kind, _, _ in stack)
            name = None if inside_function else function_name(s[head_start:i])
            stack.append(("fn" if name else "block", line, name))
            head_start = i + 1
        elif c == "}":
            if stack:
                kind, start, name = stack.pop()
                if kind == "fn":
                    found.append((name, start, line))
            head_start = i + 1
        elif c == ";":
            head_start = i + 1
    return found


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("paths", nargs="*", default=["src"])
    p.add_argument("--limit", type=int, default=80)
    a = p.parse_args()
    too_long = []
    for root in a.paths:
        files = [root] if os.path.isfile(root) else [os.path.join(d, f) for d, _, fs in os.walk(root) for f in fs]
        for path in sorted(files):
            if not path.endswith((".cpp", ".h")):
                continue
            with open(path, encoding="utf-8") as f:
                for name, first, last in functions(f.read()):
                    if last - first + 1 > a.limit:
                        too_long.append((last - first + 1, path, first, name))
    for length, path, first, name in sorted(too_long, reverse=True):
        print(f"{path}:{first}: {name}: {length} lines (limit {a.limit})")
    if not too_long:
        print(f"no function longer than {a.limit} lines")
    return 1 if too_long else 0


if __name__ == "__main__":
    sys.exit(main())
