"""docs/architecture.md describes the code as it is: every folder of lib/ and every header of
include/simbob/ (tool/ included) appears in it by name, no public header shares its name with a
file of cmd/, and no function in lib/ is over 120 lines unless the document names it as a
table-driven dispatch (its "Long functions" list).

Usage: architecture_doc.py REPO   (exit 1 naming every miss)
"""
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import cmd_thin  # noqa: E402  (the brace-counting function finder)

MAX_LIB_FUNCTION_LINES = 120


def allowed_long_functions(doc):
    """The names in the bullet list under the heading 'Long functions'."""
    section = re.search(r"^#+ Long functions\n(.*?)(?=^#|\Z)", doc, re.M | re.S)
    return set(re.findall(r"^- `([A-Za-z_:~]+)`", section.group(1), re.M)) if section else set()


def main(repo):
    repo = Path(repo)
    doc = (repo / "docs" / "architecture.md").read_text(encoding="utf-8")
    problems = []
    for folder in sorted(p for p in (repo / "lib").iterdir() if p.is_dir()):
        if f"lib/{folder.name}" not in doc:
            problems.append(f"docs/architecture.md does not name the folder lib/{folder.name}")
    include = repo / "include" / "simbob"
    for header in sorted(include.rglob("*.h*")):
        rel = header.relative_to(include).as_posix()
        if rel not in doc:
            problems.append(f"docs/architecture.md does not name the header {rel} (include/simbob/{rel})")
    cmd_stems = {p.stem for p in (repo / "cmd" / "simbob").glob("*.cpp")}
    for header in sorted(include.glob("*.h*")):  # the public ones (tool/ is the tool's own)
        if header.stem in cmd_stems:
            problems.append(f"include/simbob/{header.name} shares its name with cmd/simbob/{header.stem}.cpp")
    allowed = allowed_long_functions(doc)
    cmd_thin.MAX_FUNCTION_LINES = MAX_LIB_FUNCTION_LINES
    for source in sorted((repo / "lib").rglob("*")):
        if source.suffix not in (".cpp", ".h"):
            continue
        found, _ = cmd_thin.long_functions(source)
        for line in found:
            if not any(re.search(r"\b" + re.escape(name.split("::")[-1]) + r"\s*\(", line) for name in allowed):
                problems.append(line + " (not a dispatch named under 'Long functions' in docs/architecture.md)")
    for p in problems:
        print(p)
    print("architecture: " + ("ok" if not problems else f"{len(problems)} problems"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
