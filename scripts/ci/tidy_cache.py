#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The clang-tidy results cache of the static analysis stage (docs/hardening.md, "Static
analysis"): a translation unit whose whole analysis input is unchanged since clang-tidy last
found it clean is not analysed again.

The key of a translation unit is the SHA-256 of everything its analysis reads: clang-tidy's
version (not the host CPU it reports), the .clang-tidy file, the compile command (the checkout's path written as @ROOT@), and
the unit preprocessed with that command, comments kept (-E -C: a NOLINT comment is input too),
line markers kept (a NOLINTNEXTLINE is about the next line), the checkout's path written as
@ROOT@. Any change to the file, to any header it includes (ours, Eigen's, the standard
library's), to its flags, to the checks or to the tool gives another key, and the unit is
analysed. Only units found clean are recorded; a unit with a finding is never in the cache.

  tidy_cache.py select DB REGEX ROOT CACHE TODO KEYS
      for each unit of the compilation database DB whose file matches REGEX: its key; the units
      whose key is not in CACHE (one "KEY PATH" a line, PATH relative to ROOT) go to TODO (one
      anchored regex of its absolute path a line, as run-clang-tidy takes files), every unit's
      "KEY PATH" to KEYS
  tidy_cache.py update KEYS CACHE
      after clang-tidy found every unit of KEYS clean: their lines replace those of the same
      paths in CACHE (written sorted by path; other paths' lines stay)
"""
import hashlib
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor


def command_of(entry):
    if "arguments" in entry:
        return list(entry["arguments"])
    return shlex.split(entry["command"])


def preprocess_args(args):
    """The compile command turned into one that preprocesses to standard output."""
    out = []
    skip = False
    for a in args:
        if skip:
            skip = False
            continue
        if a in ("-o", "-MF", "-MT", "-MQ"):
            skip = True
            continue
        if a in ("-c", "-MD", "-MMD") or a.startswith("-o"):
            continue
        out.append(a)
    return out + ["-E", "-C", "-o", "-"]


def key_of(entry, root, salt):
    args = command_of(entry)
    if args and os.path.basename(args[0]) == "ccache":
        args = args[1:]
    done = subprocess.run(preprocess_args(args), cwd=entry["directory"], capture_output=True)
    if done.returncode != 0:
        return None  # not preprocessed here: analysed (clang-tidy says why it cannot)
    h = hashlib.sha256(salt)
    h.update(" ".join(args).replace(root, "@ROOT@").encode())
    h.update(b"\0")
    h.update(done.stdout.replace(root.encode(), b"@ROOT@"))
    return h.hexdigest()


def tool_version(tidy):
    """clang-tidy's --version without its "Host CPU:" line: the CPU the tool runs on (LLVM's
    guess, "(unknown)" on some virtual machines), which its analysis does not depend on. With
    it, every key changed from one machine to the next, and CI analysed every unit again."""
    out = subprocess.run([tidy, "--version"], capture_output=True).stdout
    return b"".join(line for line in out.splitlines(keepends=True)
                    if not line.strip().startswith(b"Host CPU:"))


def read_keys(path):
    """{PATH: {KEY, ...}} of a "KEY PATH" file (a file compiled by two targets has two keys)."""
    keys = {}
    if os.path.exists(path):
        with open(path) as f:
            for line in f:
                if line.strip():
                    key, unit = line.split()
                    keys.setdefault(unit, set()).add(key)
    return keys


def select(db, regex, root, cache_path, todo_path, keys_path):
    root = os.path.realpath(root)
    with open(db) as f:
        entries = [e for e in json.load(f) if re.search(regex, e["file"])]
    tidy = shutil.which("clang-tidy-14")  # (none: no key matches a clean one; all analysed)
    version = tool_version(tidy) if tidy else b"-"
    with open(os.path.join(root, ".clang-tidy"), "rb") as f:
        salt = version + b"\0" + f.read() + b"\0"
    cache = read_keys(cache_path)
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        keys = list(pool.map(lambda e: key_of(e, root, salt), entries))
    todo, lines = [], []
    for entry, key in zip(entries, keys):
        path = os.path.relpath(entry["file"], root)
        if key is None or key not in cache.get(path, ()):
            todo.append(entry["file"])
        if key is not None:
            lines.append(f"{key} {path}\n")
    with open(todo_path, "w") as f:
        f.writelines("^" + re.escape(p) + "$\n" for p in todo)
    with open(keys_path, "w") as f:
        f.writelines(lines)
    print(f"clang-tidy cache: {len(entries) - len(todo)} of {len(entries)} units unchanged "
          f"since found clean, {len(todo)} to analyse")


def update(keys_path, cache_path):
    entries = read_keys(cache_path)
    entries.update(read_keys(keys_path))
    with open(cache_path, "w") as f:
        f.writelines(f"{key} {unit}\n" for unit in sorted(entries) for key in sorted(entries[unit]))


def main(argv):
    if len(argv) == 8 and argv[1] == "select":
        select(*argv[2:])
    elif len(argv) == 4 and argv[1] == "update":
        update(*argv[2:])
    else:
        sys.stderr.write(__doc__)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
