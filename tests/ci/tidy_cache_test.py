#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The clang-tidy results cache (scripts/ci/tidy_cache.py): a unit's key changes with anything
its analysis reads (its code, a header it includes, a NOLINT comment, its flags, the checks) and
with nothing else (the checkout's path, a header it does not include); a unit is listed to
analyse exactly when its key is not in the cache; an update keeps other paths' keys."""
import importlib.util
import json
import os
import shutil
import sys
import tempfile
import unittest

spec = importlib.util.spec_from_file_location("tidy_cache", sys.argv.pop(1))
tidy_cache = importlib.util.module_from_spec(spec)
spec.loader.exec_module(tidy_cache)


class Tree:
    """A checkout of two units, a.cpp (including a.h) and b.cpp, with its compile database."""

    def __init__(self, root, flags="-O2"):
        self.root = root
        os.makedirs(os.path.join(root, "src"), exist_ok=True)
        self.write(".clang-tidy", "Checks: '-*,bugprone-*'\n")
        self.write("src/a.h", "inline int twice(int v) { return 2 * v; }\n")
        self.write("src/other.h", "inline int thrice(int v) { return 3 * v; }\n")
        self.write("src/a.cpp", '#include "a.h"\nint a() { return twice(1); }  // plain\n')
        self.write("src/b.cpp", "int b() { return 2; }\n")
        self.flags = flags
        self.database()

    def write(self, rel, text):
        with open(os.path.join(self.root, rel), "w") as f:
            f.write(text)

    def database(self):
        entries = [{"directory": self.root,
                    "command": f"c++ {self.flags} -I{self.root}/src -o x.o "
                               f"-c {self.root}/src/{n}",
                    "file": f"{self.root}/src/{n}"} for n in ("a.cpp", "b.cpp")]
        self.write("compile_commands.json", json.dumps(entries))

    def select(self, cache):
        todo = os.path.join(self.root, "todo.txt")
        keys = os.path.join(self.root, "keys.txt")
        tidy_cache.select(os.path.join(self.root, "compile_commands.json"), "/src/",
                          self.root, cache, todo, keys)
        with open(todo) as f:
            listed = [line.strip() for line in f]
        with open(keys) as f:
            found = dict(reversed(line.split()) for line in f)
        return found, listed


class TidyCacheTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp()
        self.tree = Tree(os.path.join(self.dir, "one"))
        self.before, listed = self.tree.select(os.devnull)
        self.assertEqual(len(listed), 2)  # nothing cached: both analysed
        self.assertEqual(sorted(self.before), ["src/a.cpp", "src/b.cpp"])

    def tearDown(self):
        shutil.rmtree(self.dir)

    def changed(self):
        after, _ = self.tree.select(os.devnull)
        return sorted(p for p in after if after[p] != self.before[p])

    def test_the_same_tree_elsewhere_has_the_same_keys(self):
        other = Tree(os.path.join(self.dir, "elsewhere", "two"))
        keys, _ = other.select(os.devnull)
        self.assertEqual(keys, self.before)

    def test_a_change_of_the_unit_changes_its_key_only(self):
        self.tree.write("src/b.cpp", "int b() { return 3; }\n")
        self.assertEqual(self.changed(), ["src/b.cpp"])

    def test_a_change_of_an_included_header_changes_its_includers_key(self):
        self.tree.write("src/a.h", "inline int twice(int v) { return v + v; }\n")
        self.assertEqual(self.changed(), ["src/a.cpp"])

    def test_a_header_not_included_changes_nothing(self):
        self.tree.write("src/other.h", "inline int thrice(int v) { return v + v + v; }\n")
        self.assertEqual(self.changed(), [])

    def test_a_nolint_comment_changes_the_key(self):
        self.tree.write("src/a.cpp", '#include "a.h"\nint a() { return twice(1); }  // NOLINT\n')
        self.assertEqual(self.changed(), ["src/a.cpp"])

    def test_other_flags_change_every_key(self):
        self.tree.flags = "-O2 -Werror"
        self.tree.database()
        self.assertEqual(self.changed(), ["src/a.cpp", "src/b.cpp"])

    def test_other_checks_change_every_key(self):
        self.tree.write(".clang-tidy", "Checks: '-*,bugprone-*,performance-*'\n")
        self.assertEqual(self.changed(), ["src/a.cpp", "src/b.cpp"])

    def test_only_units_whose_key_is_not_cached_are_listed(self):
        cache = os.path.join(self.dir, "clean.txt")
        with open(cache, "w") as f:
            f.write(f"{self.before['src/a.cpp']} src/a.cpp\n")
        _, listed = self.tree.select(cache)
        self.assertEqual(len(listed), 1)
        self.assertTrue(listed[0].endswith("b\\.cpp$"), listed)
        # A key under another path is no key of this unit.
        with open(cache, "w") as f:
            f.write(f"{self.before['src/a.cpp']} src/b.cpp\n")
        _, listed = self.tree.select(cache)
        self.assertEqual(len(listed), 2)

    def test_an_update_replaces_its_paths_and_keeps_the_others(self):
        cache = os.path.join(self.dir, "clean.txt")
        with open(cache, "w") as f:
            f.write("1111 src/a.cpp\n2222 src/gone.cpp\n")
        keys = os.path.join(self.dir, "keys.txt")
        with open(keys, "w") as f:
            f.write(f"{self.before['src/a.cpp']} src/a.cpp\n")
        tidy_cache.update(keys, cache)
        with open(cache) as f:
            self.assertEqual(f.read(), f"{self.before['src/a.cpp']} src/a.cpp\n2222 src/gone.cpp\n")
        # A unit compiled by two targets has a key for each, both kept.
        with open(keys, "w") as f:
            f.write("3333 src/b.cpp\n4444 src/b.cpp\n")
        tidy_cache.update(keys, cache)
        with open(cache) as f:
            self.assertIn("3333 src/b.cpp\n4444 src/b.cpp\n", f.read())


if __name__ == "__main__":
    unittest.main()
