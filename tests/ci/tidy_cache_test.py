#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The clang-tidy results cache (scripts/ci/tidy_cache.py): a unit's key changes with anything
its analysis reads (its code, a header it includes, a NOLINT comment, the line its code is on,
its flags, the checks, clang-tidy's version) and with nothing else (the checkout's path, a header
it does not include, a ccache launcher); a unit is listed to analyse exactly when its key is not
in the cache, and one that does not preprocess is always listed and never keyed; an update keeps
other paths' keys and writes the file sorted."""
import importlib.util
import json
import os
import shutil
import sys
import tempfile
import unittest
from unittest import mock

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
        self.compiler = "c++"
        self.database()

    def write(self, rel, text):
        with open(os.path.join(self.root, rel), "w") as f:
            f.write(text)

    def database(self):
        entries = [{"directory": self.root,
                    "command": f"{self.compiler} {self.flags} -I{self.root}/src -o x.o "
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

    def test_code_moved_to_another_line_changes_the_key(self):
        # A NOLINTNEXTLINE then names another line: the line markers are input.
        self.tree.write("src/b.cpp", "// NOLINTNEXTLINE\nint b() { return 2; }\n")
        before, _ = self.tree.select(os.devnull)
        self.tree.write("src/b.cpp", "// NOLINTNEXTLINE\n\nint b() { return 2; }\n")
        after, _ = self.tree.select(os.devnull)
        self.assertNotEqual(after["src/b.cpp"], before["src/b.cpp"])
        self.assertEqual(after["src/a.cpp"], before["src/a.cpp"])

    def test_code_moved_from_a_header_into_the_unit_changes_the_key(self):
        # The same text, now in the main file: clang-tidy reports there what it left out of a
        # header (HeaderFilterRegex).
        self.tree.write("src/a.cpp", "inline int twice(int v) { return 2 * v; }\n"
                                     "int a() { return twice(1); }  // plain\n")
        self.assertEqual(self.changed(), ["src/a.cpp"])

    def test_a_ccache_launcher_is_no_part_of_the_key(self):
        self.tree.compiler = "ccache c++"
        self.tree.database()
        self.assertEqual(self.changed(), [])

    def test_another_clang_tidy_changes_every_key(self):
        tool = os.path.join(self.dir, "bin", "clang-tidy-14")
        os.makedirs(os.path.dirname(tool))

        def keys_with(version):
            with open(tool, "w") as f:
                f.write(f"#!/bin/sh\necho 'LLVM version {version}'\n")
            os.chmod(tool, 0o755)
            found = tool if version else None
            with mock.patch.object(tidy_cache.shutil, "which", lambda name: found):
                return self.tree.select(os.devnull)[0]

        old = keys_with("14.0.6")
        self.assertEqual(keys_with("14.0.6"), old)
        new = keys_with("14.0.7")
        self.assertEqual([p for p in new if new[p] == old[p]], [])
        # Where clang-tidy is not installed, no key is that of a unit analysed with one.
        none = keys_with(None)
        self.assertEqual([p for p in none if none[p] in (old[p], new[p])], [])

    def test_the_host_cpu_clang_tidy_names_is_no_part_of_the_key(self):
        tool = os.path.join(self.dir, "bin", "clang-tidy-14")
        os.makedirs(os.path.dirname(tool))

        def keys_with(cpu):
            with open(tool, "w") as f:
                f.write("#!/bin/sh\necho 'Debian LLVM version 14.0.6'\necho '  Optimized build.'\n"
                        f"echo '  Host CPU: {cpu}'\n")
            os.chmod(tool, 0o755)
            with mock.patch.object(tidy_cache.shutil, "which", lambda name: tool):
                return self.tree.select(os.devnull)[0]

        # The same tool on another machine: the same keys. Its version still counts.
        unknown = keys_with("(unknown)")
        self.assertEqual(keys_with("znver4"), unknown)
        with open(tool, "w") as f:
            f.write("#!/bin/sh\necho 'Debian LLVM version 14.0.7'\necho '  Host CPU: znver4'\n")
        with mock.patch.object(tidy_cache.shutil, "which", lambda name: tool):
            other = self.tree.select(os.devnull)[0]
        self.assertEqual([p for p in other if other[p] == unknown[p]], [])

    def test_a_unit_that_does_not_preprocess_is_analysed_and_never_keyed(self):
        cache = os.path.join(self.dir, "clean.txt")
        with open(cache, "w") as f:
            f.writelines(f"{key} {path}\n" for path, key in self.before.items())
        self.tree.write("src/b.cpp", '#include "missing.h"\nint b() { return 2; }\n')
        keys, listed = self.tree.select(cache)
        self.assertEqual(len(listed), 1)
        self.assertTrue(listed[0].endswith("b\\.cpp$"), listed)
        self.assertEqual(sorted(keys), ["src/a.cpp"])  # so no update can record it clean

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

    def updated(self, keys_text, cache_text=None):
        """The cache file after an update with the KEYS file keys_text (cache_text: the cache
        file before; None: as the last update left it)."""
        cache = os.path.join(self.dir, "clean.txt")
        keys = os.path.join(self.dir, "keys.txt")
        if cache_text is not None:
            with open(cache, "w") as f:
                f.write(cache_text)
        with open(keys, "w") as f:
            f.write(keys_text)
        tidy_cache.update(keys, cache)
        with open(cache) as f:
            return f.read()

    def test_an_update_replaces_its_paths_and_keeps_the_others(self):
        a = self.before["src/a.cpp"]
        self.assertEqual(self.updated(f"{a} src/a.cpp\n", "1111 src/a.cpp\n2222 src/gone.cpp\n"),
                         f"{a} src/a.cpp\n2222 src/gone.cpp\n")
        # A unit compiled by two targets has a key for each, both kept.
        self.assertIn("3333 src/b.cpp\n4444 src/b.cpp\n",
                      self.updated("3333 src/b.cpp\n4444 src/b.cpp\n"))

    def test_an_update_writes_the_file_sorted_by_path_then_key(self):
        self.assertEqual(self.updated("4444 src/b.cpp\n3333 src/b.cpp\n1111 src/a.cpp\n",
                                      "2222 src/gone.cpp\n"),
                         "1111 src/a.cpp\n3333 src/b.cpp\n4444 src/b.cpp\n2222 src/gone.cpp\n")

if __name__ == "__main__":
    unittest.main()
