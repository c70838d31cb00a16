#!/usr/bin/env python3
"""Mutation harness: plants each mutant of tests/mutants/mutants.json in a scratch copy of the
tree, builds only the test targets the mutant names, runs the tests that should catch it and
reports killed / survived / error per mutant (docs/testing.md).

A mutant is a list of edits, each (file, exact `old` text or a `regex`, `new` text); the old
text or the regex must match exactly once, else the mutant is an error (never skipped). The
scratch tree (a copy of the tracked and untracked-but-not-ignored files) and its one build
directory are reused across mutants, so each mutant is an incremental build; the mutated file
is restored after each mutant. Before the mutants, the same tests run on the unmutated tree:
a test that fails there cannot kill anything (error).

Exit status: 0 when every mutant selected was killed, 1 otherwise, 2 on a usage error.
Python 3 standard library only.
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_SOURCE = os.path.dirname(os.path.dirname(HERE))


def log(message):
    print(message, file=sys.stderr, flush=True)


def load_mutants(path):
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    mutants = data["mutants"]
    names = set()
    for m in mutants:
        for key in ("name", "edits", "targets", "tests"):
            if key not in m:
                raise SystemExit(f"{path}: mutant {m.get('name', '?')} lacks '{key}'")
        if m["name"] in names:
            raise SystemExit(f"{path}: mutant {m['name']} named twice")
        names.add(m["name"])
        for e in m["edits"]:
            if "file" not in e or "new" not in e or (("old" in e) == ("regex" in e)):
                raise SystemExit(f"{path}: mutant {m['name']}: an edit needs file, new and "
                                 "exactly one of old or regex")
    return mutants


def tracked_files(source):
    out = subprocess.run(
        ["git", "-C", source, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
        check=True, capture_output=True).stdout
    return [p for p in out.decode().split("\0") if p and not p.startswith("build/")]


def sync_tree(source, dest):
    """Copies the files that differ (content), so unchanged files keep their times and the
    scratch build stays incremental."""
    copied = 0
    for rel in tracked_files(source):
        src = os.path.join(source, rel)
        dst = os.path.join(dest, rel)
        if not os.path.isfile(src):
            continue  # deleted in the work tree
        if os.path.isfile(dst):
            with open(src, "rb") as a, open(dst, "rb") as b:
                if a.read() == b.read():
                    continue
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        shutil.copy2(src, dst)
        copied += 1
    return copied


def apply_edits(tree, edits):
    """Applies every edit; returns {path: original text} to restore, or raises ValueError
    naming the edit that did not match exactly once (nothing is left modified then)."""
    originals = {}
    try:
        for e in edits:
            path = os.path.join(tree, e["file"])
            if not os.path.isfile(path):
                raise ValueError(f"{e['file']}: no such file")
            with open(path, encoding="utf-8") as f:
                text = f.read()
            originals.setdefault(path, text)
            if "old" in e:
                count = text.count(e["old"])
                if count != 1:
                    raise ValueError(f"{e['file']}: old text found {count} times (needs 1)")
                text = text.replace(e["old"], e["new"], 1)
            else:
                pattern = re.compile(e["regex"], re.MULTILINE)
                count = len(pattern.findall(text))
                if count != 1:
                    raise ValueError(f"{e['file']}: regex matched {count} times (needs 1)")
                text = pattern.sub(e["new"], text, count=1)
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
    except ValueError:
        restore(originals)
        raise
    return originals


def restore(originals):
    for path, text in originals.items():
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)


def run(cmd, env, log_path, timeout=None):
    with open(log_path, "a", encoding="utf-8") as out:
        out.write("$ " + " ".join(cmd) + "\n")
        out.flush()
        try:
            return subprocess.run(cmd, env=env, stdout=out, stderr=subprocess.STDOUT,
                                  timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            out.write(f"timed out after {timeout} s\n")
            return None


def tests_key(mutant):
    return json.dumps(mutant["tests"], sort_keys=True)


def run_tests(build, tests, env, log_path, timeout):
    """0: every test passed; (1, first failed case): a test failed (or crashed, or timed
    out); None: a test
    executable is missing or its filter selects no test. Each entry names a GoogleTest
    executable (`exe`, relative to the build directory) and a `filter` (--gtest_filter)."""
    failed, killer = False, ""
    for t in tests:
        exe = os.path.join(build, t["exe"])
        if not os.path.isfile(exe):
            with open(log_path, "a", encoding="utf-8") as out:
                out.write(f"no executable {exe}\n")
            return None
        cmd = [exe, "--gtest_filter=" + t.get("filter", "*"), "--gtest_brief=1"]
        mark = os.path.getsize(log_path)
        rc = run(cmd, env, log_path, timeout)
        with open(log_path, encoding="utf-8", errors="replace") as f:
            f.seek(mark)
            output = f.read()
        if rc == 0 and re.search(r"\[  PASSED  \] 0 tests", output):
            with open(log_path, "a", encoding="utf-8") as out:
                out.write(f"the filter {t.get('filter')} selects no test\n")
            return None
        if rc != 0:
            # Fails, crashes or times out: the mutant is caught. Name the first failed case.
            failed = True
            first = re.search(r"^\[  FAILED  \] (\S+)", output, re.MULTILINE)
            killer = first.group(1).rstrip(",") if first else f"{os.path.basename(exe)} (exit {rc})"
            break
    return (1, killer) if failed else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--source", default=DEFAULT_SOURCE, help="the repository (default: this one)")
    parser.add_argument("--scratch", help="scratch directory (default: SOURCE/build/mutants)")
    parser.add_argument("--mutants", default=os.path.join(HERE, "mutants.json"))
    parser.add_argument("--only", help="regex on mutant names: run these only")
    parser.add_argument("--jobs", type=int, default=2, help="build parallelism")
    parser.add_argument("--timeout", type=int, default=900, help="seconds per test")
    parser.add_argument("--no-baseline", action="store_true",
                        help="skip running the tests on the unmutated tree first")
    parser.add_argument("--list", action="store_true", help="list the mutants and exit")
    parser.add_argument("--check", action="store_true",
                        help="check that every edit applies to SOURCE (no build) and exit")
    args = parser.parse_args()

    mutants = load_mutants(args.mutants)
    if args.only:
        mutants = [m for m in mutants if re.search(args.only, m["name"])]
        if not mutants:
            log(f"run_mutants: no mutant matches {args.only!r}")
            return 2
    if args.list:
        for m in mutants:
            files = ", ".join(sorted({e["file"] for e in m["edits"]}))
            print(f"{m['name']:32} {files}")
        return 0

    source = os.path.abspath(args.source)
    if args.check:
        bad = 0
        for m in mutants:
            for e in m["edits"]:
                with open(os.path.join(source, e["file"]), encoding="utf-8") as f:
                    text = f.read()
                count = (text.count(e["old"]) if "old" in e else
                         len(re.findall(e["regex"], text, re.MULTILINE)))
                if count != 1:
                    bad += 1
                    print(f"{m['name']}: {e['file']}: matches {count} times (needs 1)")
        print(f"{len(mutants) - bad if bad == 0 else 'not all'} mutants apply" if bad == 0
              else f"{bad} edits do not apply")
        return 1 if bad else 0

    start = time.monotonic()
    scratch = os.path.abspath(args.scratch or os.path.join(source, "build", "mutants"))
    # The build directory sits where the ci preset puts it (SOURCE/build/ci), so compile
    # commands carry the same relative paths and ccache (CCACHE_BASEDIR) shares its objects.
    tree = os.path.join(scratch, "src")
    build = os.path.join(tree, "build", "ci")
    logs = os.path.join(scratch, "logs")
    os.makedirs(tree, exist_ok=True)
    os.makedirs(logs, exist_ok=True)
    copied = sync_tree(source, tree)
    log(f"run_mutants: scratch tree {tree} ({copied} files copied), build {build}")

    env = dict(os.environ)
    if shutil.which("ccache") and "CMAKE_CXX_COMPILER_LAUNCHER" not in env:
        env["CMAKE_CXX_COMPILER_LAUNCHER"] = "ccache"
    env.setdefault("CCACHE_BASEDIR", tree)
    env.setdefault("CCACHE_NOHASHDIR", "1")
    setup_log = os.path.join(logs, "setup.log")
    open(setup_log, "w").close()
    rc = run(["cmake", "-S", tree, "-B", build, "-G", "Unix Makefiles",
              "-DCMAKE_BUILD_TYPE=Release", "-DKASUMI_WERROR=ON", "-DKASUMI_BUILD_TESTS=ON",
              "-DKASUMI_BUILD_BENCH=OFF", "-DKASUMI_BUILD_PYTHON=OFF", "-DKASUMI_MUTANTS=OFF"],
             env, setup_log)
    if rc != 0:
        log(f"run_mutants: configuring the scratch tree failed (see {setup_log})")
        return 1

    targets = sorted({t for m in mutants for t in m["targets"]})
    log(f"run_mutants: building {len(targets)} test targets unmutated")
    if run(["cmake", "--build", build, "-j", str(args.jobs), "--target"] + targets, env,
           setup_log) != 0:
        log(f"run_mutants: the unmutated build failed (see {setup_log})")
        return 1

    baseline = {}
    if not args.no_baseline:
        for m in mutants:
            key = tests_key(m)
            if key not in baseline:
                log(f"run_mutants: baseline for {m['name']}")
                baseline[key] = run_tests(build, m["tests"], env, setup_log, args.timeout)

    rows = []
    for m in mutants:
        t0 = time.monotonic()
        log_path = os.path.join(logs, m["name"] + ".log")
        open(log_path, "w").close()
        key = tests_key(m)
        status, note = None, ""
        if baseline.get(key, 0) != 0:
            status = "error"
            note = "tests fail unmutated" if baseline[key] else "a test is missing"
        if status is None:
            try:
                originals = apply_edits(tree, m["edits"])
            except ValueError as e:
                status, note = "error", str(e)
        if status is None:
            try:
                rc = run(["cmake", "--build", build, "-j", str(args.jobs), "--target"] +
                         m["targets"], env, log_path)
                if rc != 0:
                    status, note = "error", "the mutant does not build"
                else:
                    result = run_tests(build, m["tests"], env, log_path, args.timeout)
                    if result is None:
                        status, note = "error", "a test is missing"
                    elif result == 0:
                        status = "survived"
                    else:
                        status, note = "killed", "by " + result[1]
            finally:
                restore(originals)
        seconds = time.monotonic() - t0
        files = ", ".join(sorted({e["file"] for e in m["edits"]}))
        rows.append((m["name"], files, status, seconds, note))
        log(f"run_mutants: {m['name']}: {status} ({seconds:.0f} s){' - ' + note if note else ''}")

    # Leave the scratch build matching the unmutated tree's sources (restored files).
    width = max(len(r[0]) for r in rows)
    fwidth = max(len(r[1]) for r in rows)
    print(f"{'mutant':{width}}  {'file':{fwidth}}  {'result':8}  seconds")
    for name, files, status, seconds, note in rows:
        print(f"{name:{width}}  {files:{fwidth}}  {status:8}  {seconds:7.0f}"
              + (f"  ({note})" if note else ""))
    killed = sum(1 for r in rows if r[2] == "killed")
    total = time.monotonic() - start
    print(f"{killed} of {len(rows)} mutants killed; total run time {total:.0f} s "
          f"({total / 60:.1f} min); logs in {logs}")
    return 0 if killed == len(rows) else 1


if __name__ == "__main__":
    sys.exit(main())
