#!/usr/bin/env bash
# The documentation stands on its own:
#   - every relative link and image in README.md and docs/*.md names a file of the repository
#     (outside code blocks and code spans), and a `#fragment` names a heading of its target
#     (GitHub's heading anchors);
#   - no file of the repository points at the original guide in the folder beside the
#     repository (a path through "shared" one level up, or its "seed" folder), so nothing
#     depends on the guide lying beside the repository.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

check "no file of the repository points at the guide outside it"
cd "$REPO"
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  git ls-files -z >"$WORK/files"
else  # a source tarball: every file but build output
  find . -path ./build -prune -o -path './build-*' -prune -o -type f -print0 >"$WORK/files"
fi
[[ -s "$WORK/files" ]] || fail "no files listed in $REPO"
# The patterns are written so that this file does not match them itself.
hits=$(xargs -0 grep -I -l -E -e '\.\./shared' -e 'shared/se[e]d' -- <"$WORK/files" 2>/dev/null || true)
[[ -z "$hits" ]] || fail "these files point at the guide outside the repository: $hits"
cd "$WORK"

check "README.md and every docs/*.md link only to files and headings that exist"
/usr/bin/python3 - "$REPO" <<'PY' || fail "broken links (above)"
import os, re, sys
repo = sys.argv[1]
docs = ["README.md"] + sorted("docs/" + f for f in os.listdir(os.path.join(repo, "docs")) if f.endswith(".md"))

def prose(path, spans=False):
    """The lines of a Markdown file outside fenced code blocks, with code spans blanked
    (kept with spans=True)."""
    out, fence = [], False
    for n, line in enumerate(open(os.path.join(repo, path), encoding="utf-8"), start=1):
        if line.lstrip().startswith("```"):
            fence = not fence
            continue
        if not fence:
            out.append((n, line if spans else re.sub(r"`[^`]*`", "``", line)))
    return out

def slug(heading):
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    s = heading.strip().lower().replace("`", "")
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")

anchors = {}
def anchors_of(path):
    if path not in anchors:
        seen, found = {}, set()
        for _, line in prose(path, spans=True):
            m = re.match(r"#{1,6} (.*)", line)
            if not m:
                continue
            base = slug(m.group(1))
            k = seen.get(base, 0)
            found.add(base if k == 0 else f"{base}-{k}")
            seen[base] = k + 1
        anchors[path] = found
    return anchors[path]

bad, count = [], 0
for doc in docs:
    for n, line in prose(doc):
        for target in re.findall(r"\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)", line):
            if re.match(r"[a-z][a-z0-9+.-]*:", target):  # https:, mailto:
                continue
            count += 1
            path, _, frag = target.partition("#")
            dest = os.path.normpath(os.path.join(os.path.dirname(doc), path)) if path else doc
            full = os.path.join(repo, dest)
            if dest.startswith(".."):
                bad.append(f"{doc}:{n}: {target}: points outside the repository")
            elif not os.path.exists(full):
                bad.append(f"{doc}:{n}: {target}: no file {dest}")
            elif frag and dest.endswith(".md") and frag not in anchors_of(dest):
                bad.append(f"{doc}:{n}: {target}: {dest} has no heading with the anchor #{frag}")
if bad:
    sys.exit("\n".join(bad))
if count < 20:
    sys.exit(f"only {count} relative links found: is the link pattern still right?")
print(f"{count} relative links in {len(docs)} files, all there")
PY

say "ok"
