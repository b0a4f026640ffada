"""cmd/ is a thin client of the library: no file in it over 300 lines, no function over 80.

Usage: cmd_thin.py DIR...  (exit 1 naming every file and function over the limits)
Functions are found by their braces: a `{` opened at namespace or class scope after a
parenthesised signature starts one, its matching `}` ends it; braces in string and character
literals and in comments do not count.
"""
import re
import sys
from pathlib import Path

MAX_FILE_LINES = 300
MAX_FUNCTION_LINES = 80


def code_only(line, in_comment):
    """The line without comments and literals; and whether a /* comment is still open."""
    out = []
    i = 0
    while i < len(line):
        if in_comment:
            end = line.find("*/", i)
            if end < 0:
                return "".join(out), True
            i, in_comment = end + 2, False
        elif line.startswith("//", i):
            break
        elif line.startswith("/*", i):
            in_comment = True
            i += 2
        elif line[i] in "\"'":
            quote = line[i]
            j = i + 1
            while j < len(line) and line[j] != quote:
                j += 2 if line[j] == "\\" else 1
            out.append(quote + quote)
            i = j + 1
        elif line.startswith('R"(', i):
            end = line.find(')"', i)
            i = len(line) if end < 0 else end + 2
        else:
            out.append(line[i])
            i += 1
    return "".join(out), in_comment


def long_functions(path):
    lines = path.read_text(encoding="utf-8").split("\n")
    found = []
    stack = []  # per open brace: "scope" (namespace, class, struct, enum, extern) or "function" or "inner"
    start = 0
    head = ""  # code since the last ; { or }: the declaration a brace opens
    in_comment = False
    for number, raw in enumerate(lines, 1):
        code, in_comment = code_only(raw, in_comment)
        for ch in code:
            if ch == "{":
                at_scope = all(kind == "scope" for kind in stack)
                if at_scope and re.search(r"\b(namespace|class|struct|enum|union|extern)\b", head) and "(" not in head:
                    stack.append("scope")
                elif at_scope and "(" in head:
                    stack.append("function")
                    start = number
                elif at_scope:
                    stack.append("scope")  # an initializer or a nameless block at scope level
                else:
                    stack.append("inner")
                head = ""
            elif ch == "}":
                kind = stack.pop() if stack else "scope"
                if kind == "function" and number - start + 1 > MAX_FUNCTION_LINES:
                    name = re.sub(r"\s+", " ", lines[start - 1].strip())[:70]
                    found.append(f"{path}:{start}: a function of {number - start + 1} lines (at most "
                                 f"{MAX_FUNCTION_LINES}): {name}")
                head = ""
            elif ch == ";":
                head = ""
            else:
                head += ch
        head += " "
    return found, len(lines) - (1 if lines and lines[-1] == "" else 0)


def main(dirs):
    problems = []
    files = sorted(p for d in dirs for p in Path(d).rglob("*") if p.suffix in (".cpp", ".h", ".in"))
    if not files:
        problems.append("no source files in " + " ".join(dirs))
    for f in files:
        functions, count = long_functions(f)
        if count > MAX_FILE_LINES:
            problems.append(f"{f}: {count} lines (at most {MAX_FILE_LINES})")
        problems.extend(functions)
    for p in problems:
        print(p)
    print(f"checked {len(files)} files: {'ok' if not problems else str(len(problems)) + ' over the limits'}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
