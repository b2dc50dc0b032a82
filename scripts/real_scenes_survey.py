#!/usr/bin/env python3
"""Survey: how many real-world scene files load, and the first error of each that does not.

Extracts the newest commit of each fetched repository (git directories as the `fetch` tool
leaves them, under $MIRROR, default /work/.mirror) into a scratch folder, finds every XML
file whose root element is <scene>, loads each with the scene crate's `load_survey` example
(parse + build, no render) and prints a table of first errors grouped by message, most
frequent first, then the totals.

    python3 scripts/real_scenes_survey.py [owner+name ...]   # default: every mirror found
    SURVEY_VERBOSE=1 ...                                      # also list every file's result

Run from the repository root; it builds the example with cargo (release).
"""
import collections
import os
import re
import subprocess
import sys

MIRROR = os.environ.get("MIRROR", "/work/.mirror")
SCRATCH = os.environ.get("SURVEY_DIR", "/tmp/tessera-survey")


def extract(name):
    """Extracts a mirror's HEAD into SCRATCH/name (once) and returns that folder."""
    out = os.path.join(SCRATCH, name)
    if os.path.isdir(out):
        return out
    git_dir = os.path.join(MIRROR, name, "repo")
    tree = subprocess.run(["git", "--git-dir", git_dir, "ls-tree", "-r", "-z", "HEAD"],
                          check=True, capture_output=True).stdout.split(b"\0")
    blobs = []
    for entry in tree:
        if not entry:
            continue
        meta, path = entry.split(b"\t", 1)
        mode, kind, oid = meta.split()
        if kind == b"blob" and mode != b"120000":
            blobs.append((oid, path.decode("utf-8", "replace")))
    # Snapshots lack their largest files: `git cat-file --batch` says "missing" for those.
    batch = subprocess.run(["git", "--git-dir", git_dir, "cat-file", "--batch"],
                           input=b"".join(o + b"\n" for o, _ in blobs),
                           check=True, capture_output=True).stdout
    at = 0
    for _, path in blobs:
        eol = batch.index(b"\n", at)
        header = batch[at:eol].split()
        at = eol + 1
        if header[-1] == b"missing":
            continue
        size = int(header[2])
        target = os.path.join(out + ".part", path)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        with open(target, "wb") as f:
            f.write(batch[at:at + size])
        at += size + 1
    os.rename(out + ".part", out)
    return out


def scene_files(root):
    """XML files under root whose first element is <scene ...>."""
    found = []
    for d, _, files in os.walk(root):
        for f in files:
            if not f.lower().endswith(".xml"):
                continue
            p = os.path.join(d, f)
            try:
                head = open(p, "rb").read(4096).decode("utf-8", "replace")
            except OSError:
                continue
            head = re.sub(r"<\?.*?\?>|<!--.*?-->", "", head, flags=re.S)
            if re.match(r"\s*<scene[\s>]", head):
                found.append(p)
    return sorted(found)


def normalize(msg):
    """A first error without its location and quoted names, to group alike errors."""
    msg = re.sub(r"^\S+?:\d+:\d+: ", "", msg)
    msg = re.sub(r"^/\S+?: ", "", msg)
    msg = re.sub(r'"[^"]*"', '"…"', msg)
    msg = re.sub(r"\(first declared at [^)]*\)", "(…)", msg)
    return msg[:110]


def main():
    names = sys.argv[1:] or sorted(
        n for n in os.listdir(MIRROR) if os.path.isdir(os.path.join(MIRROR, n, "repo")))
    files = []
    for n in names:
        files += scene_files(extract(n))
    subprocess.run(["cargo", "build", "-q", "--release", "-p", "tessera-scene",
                    "--example", "load_survey"], check=True)
    exe = os.path.join("target", "release", "examples", "load_survey")
    results = []
    for i in range(0, len(files), 50):
        out = subprocess.run([exe] + files[i:i + 50], capture_output=True, text=True).stdout
        results += out.splitlines()
    ok = [r for r in results if r.startswith("OK ")]
    errs = [r[4:].split("\t", 1) for r in results if r.startswith("ERR ")]
    groups = collections.Counter(normalize(e[1] if len(e) > 1 else "") for e in errs)
    if os.environ.get("SURVEY_VERBOSE"):
        for r in results:
            print(r.replace(SCRATCH + "/", ""))
        print()
    print(f"{'files':>5}  first error")
    for msg, n in groups.most_common():
        print(f"{n:>5}  {msg}")
    per_repo = collections.Counter()
    for r in ok:
        per_repo[r[3:].replace(SCRATCH + "/", "").split("/")[0]] += 1
    print()
    for n in names:
        total = sum(1 for f in files if f.startswith(os.path.join(SCRATCH, n) + "/"))
        print(f"{n}: {per_repo[n]}/{total} load")
    print(f"total: {len(ok)}/{len(results)} scene files load")


if __name__ == "__main__":
    main()
