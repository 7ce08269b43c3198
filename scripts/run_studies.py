#!/usr/bin/env python3
"""Runs studies (studies/<name>/) into results/<name>/: the engine of scripts/main.sh.

    run_studies.py [--all | NAME ...] [--jobs N] [--list] [--bin DIR]

No name: the default main job, the studies that studies/index.toml marks `main = "full"` (into results/<name>/) or
`main = "quick"` (their --quick case, into BUILD/quick/<name>/, leaving the committed results alone). --all: every study,
in full. NAME ...: those studies, in full.

Before it starts it prints the plan and the estimated wall time, from results/timings.csv (the wall time of each
study's last full run, rewritten by this script) and a list schedule on N workers; then a line per study as it
starts and ends, with elapsed and remaining time. Independent studies run side by side (--jobs, default the number of
cores); a study marked `alone` (a speed measurement) runs with nothing beside it, and `after` orders studies that read
another's results. Each study is one process; its output goes to BUILD/logs/<name>.log. Running side by side changes
no result: the drivers take no input from each other except through `after`, and those that run cases concurrently
give each case its own result slot (timing columns aside, which is why the speed studies run alone).

A study is studies/<name>/main.cpp (built to BIN/study_<name>, called as `study_<name> --out DIR [--quick]`), or
studies/<name>/run.sh (called as `run.sh BIN DIR`); then its plot.py DIR and the rendering of summary.md from
summary.md.in. At the end the results map results/README.md is regenerated (scripts/results_map.py), unless only
quick cases ran. Exit status: 0 when every study succeeded, 1 otherwise (the failing studies and their logs listed).
"""
import argparse
import csv
import datetime
import heapq
import os
import subprocess
import sys
import threading
import time
import tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PYTHON = os.environ.get("PYTHON", "/usr/bin/python3")
TIMINGS = os.path.join(ROOT, "results", "timings.csv")
TIMING_FIELDS = ["study", "wall_s", "jobs", "load_before", "date", "commit", "source"]
# source: "main.sh" (this script timed the whole study: driver, plot, summary) or "summary.json" (the wall time the
# driver recorded itself, taken over once from a run before this file existed: the driver part only)
DEFAULT_ESTIMATE_S = 60.0  # a study never timed (new): assumed one minute, and the plan says so


def rel(path):
    """A path as the commands see it: relative to the repository (their working directory), so that what the studies
    record about their own invocation (summary.json, summary.md) names no path outside the repository."""
    return os.path.relpath(path, ROOT)


def load_index():
    with open(os.path.join(ROOT, "studies", "index.toml"), "rb") as f:
        index = tomllib.load(f)
    for name, entry in index.items():
        unknown = set(entry) - {"family", "main", "after", "alone", "needs", "estimate_min",
                               "question", "sources", "headline", "extract", "summary"}  # the last five: results map
        if unknown:
            sys.exit(f"run_studies: studies/index.toml [{name}]: unknown field(s) {', '.join(sorted(unknown))}")
        if entry.get("main") not in (None, "full", "quick"):
            sys.exit(f"run_studies: studies/index.toml [{name}]: main must be \"full\" or \"quick\"")
        for dep in entry.get("after", []):
            if dep not in index:
                sys.exit(f"run_studies: studies/index.toml [{name}]: after names unknown study '{dep}'")
    return index


def load_timings():
    timings = {}
    if os.path.exists(TIMINGS):
        with open(TIMINGS, newline="", encoding="utf-8") as f:
            for row in csv.DictReader(f):
                timings[row["study"]] = row
    return timings


def save_timing(name, wall, jobs, load, lock):
    with lock:
        timings = load_timings()
        commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True).stdout.strip() or "unknown"
        timings[name] = {"study": name, "wall_s": f"{wall:.1f}", "jobs": str(jobs), "load_before": load,
                         "date": datetime.date.today().isoformat(), "commit": commit,
                         "source": "main.sh"}
        tmp = TIMINGS + ".tmp"
        with open(tmp, "w", newline="", encoding="utf-8") as f:
            w = csv.DictWriter(f, fieldnames=TIMING_FIELDS, lineterminator="\n")
            w.writeheader()
            for key in sorted(timings):
                w.writerow({k: timings[key].get(k, "") for k in TIMING_FIELDS})
        os.replace(tmp, TIMINGS)


def load_average():
    try:
        with open("/proc/loadavg") as f:
            return f.read().split()[0]
    except OSError:
        return "-"


def hms(seconds):
    seconds = int(round(seconds))
    return f"{seconds // 3600}:{seconds // 60 % 60:02d}:{seconds % 60:02d}" if seconds >= 3600 else \
        f"{seconds // 60}:{seconds % 60:02d}"


class Task:
    def __init__(self, name, entry, quick, bin_dir, build_dir):
        self.name, self.entry, self.quick = name, entry, quick
        study = os.path.join(ROOT, "studies", name)
        self.exe = os.path.join(bin_dir, "study_" + name.replace("-", "_"))
        self.script = os.path.join(study, "run.sh")
        self.out = os.path.join(build_dir, "quick", name) if quick else os.path.join(ROOT, "results", name)
        self.plot = os.path.join(study, "plot.py")
        self.template = os.path.join(study, "summary.md.in")
        self.log = os.path.join(build_dir, "logs", name + (".quick" if quick else "") + ".log")
        self.bin_dir = bin_dir
        self.after = entry.get("after", [])
        self.alone = bool(entry.get("alone", False))

    def command(self):
        if os.path.exists(self.script):
            if self.quick:
                raise SystemExit(f"run_studies: {self.name} is a run.sh study and has no --quick case")
            return ["bash", self.script, rel(self.bin_dir), rel(self.out)]
        if os.path.exists(self.exe):
            return [rel(self.exe), "--out", rel(self.out)] + (["--quick"] if self.quick else [])
        raise SystemExit(f"run_studies: {self.name}: neither {self.exe} (build it) nor {self.script} exists")

    def run(self):
        os.makedirs(self.out, exist_ok=True)
        os.makedirs(os.path.dirname(self.log), exist_ok=True)
        steps = [self.command()]
        if os.path.exists(self.plot):
            steps.append([PYTHON, rel(self.plot), rel(self.out)])
        with open(self.log, "w", encoding="utf-8") as log:
            for cmd in steps:
                log.write("$ " + " ".join(cmd) + "\n")
                log.flush()
                rc = subprocess.run(cmd, cwd=ROOT, stdout=log, stderr=subprocess.STDOUT).returncode
                if rc != 0:
                    return f"'{' '.join(cmd)}' exited with {rc}"
            if os.path.exists(self.template):
                summary = os.path.join(self.out, "summary.md")
                with open(summary + ".tmp", "w", encoding="utf-8") as md:
                    rc = subprocess.run([PYTHON, "scripts/render_summary.py", rel(self.template),
                                         rel(os.path.join(self.out, "summary.json"))], cwd=ROOT, stdout=md,
                                        stderr=log).returncode
                if rc != 0:
                    return f"render_summary.py exited with {rc}"
                os.replace(summary + ".tmp", summary)
        return None


def estimate(task, timings):
    """Seconds, and whether it is a measurement (full runs only: a quick case is assumed a tenth, at most 60 s)."""
    row = timings.get(task.name)
    if row is None:
        return 60.0 * float(task.entry.get("estimate_min", DEFAULT_ESTIMATE_S / 60.0)), False
    wall = float(row["wall_s"])
    return (min(60.0, 0.1 * wall) if task.quick else wall), not task.quick


def schedule(tasks, est, jobs):
    """Simulated wall time of the list schedule the runner uses (longest estimate first among the ready)."""
    done_at, running, clock, pending = {}, [], 0.0, list(tasks)
    while pending or running:
        ready = [t for t in pending if all(d in done_at and done_at[d] <= clock for d in t.after
                                           if d in {p.name for p in tasks})]
        ready.sort(key=lambda t: -est[t.name])
        started = False
        for t in ready:
            alone_running = any(r[2].alone for r in running)
            if alone_running or len(running) >= jobs or (t.alone and running):
                break
            heapq.heappush(running, (clock + est[t.name], t.name, t))
            pending.remove(t)
            started = True
        if running and not started:
            end, name, _ = heapq.heappop(running)
            clock, done_at[name] = end, end
        elif not running and not started:
            raise SystemExit("run_studies: the after= order has a cycle")
    return clock


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("names", nargs="*", help="studies to run in full (default: the main job)")
    ap.add_argument("--all", action="store_true", help="every study, in full (regenerates results/)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="studies side by side (default: cores)")
    ap.add_argument("--list", action="store_true", help="print the plan and the estimate, run nothing")
    ap.add_argument("--targets", action="store_true",
                    help="print the CMake targets the plan needs (one line) and exit: main.sh builds only those")
    ap.add_argument("--needs", action="store_true",
                    help="print the optional dependency groups the plan needs (e.g. 'fe': the FE reference) and exit")
    ap.add_argument("--bin", default=os.path.join(os.environ.get("BUILD_DIR", "build"), "bin"))
    args = ap.parse_args()
    if args.jobs < 1:
        sys.exit("run_studies: --jobs must be >= 1")
    if args.all and args.names:
        sys.exit("run_studies: give --all or study names, not both")
    index = load_index()
    unknown = [n for n in args.names if n not in index]
    if unknown:
        sys.exit(f"run_studies: unknown study {', '.join(unknown)} (studies/index.toml lists "
                 f"{', '.join(index)})")
    bin_dir = os.path.abspath(os.path.join(ROOT, args.bin)) if not os.path.isabs(args.bin) else args.bin
    build_dir = os.path.dirname(bin_dir)
    if args.names:
        chosen = [(n, False) for n in index if n in args.names]
    elif args.all:
        chosen = [(n, False) for n in index]
    else:
        chosen = [(n, index[n]["main"] == "quick") for n in index if "main" in index[n]]
    tasks = [Task(n, index[n], q, bin_dir, build_dir) for n, q in chosen]
    if args.needs:
        print(" ".join(sorted({g for t in tasks for g in index[t.name].get("needs", [])})))
        return 0
    if args.targets:
        if any(os.path.exists(t.script) for t in tasks):
            print("sphstab_cli sphstab_studies sphstab_benchmarks")  # run.sh studies drive benchmarks and the CLI
        else:
            print(" ".join(["sphstab_cli"] + [os.path.basename(t.exe) for t in tasks]))
        return 0
    timings = load_timings()
    est, measured = {}, {}
    for t in tasks:
        est[t.name], measured[t.name] = estimate(t, timings)
    total = schedule(tasks, est, args.jobs)
    serial = sum(est.values())
    kind = "the default main job" if not (args.all or args.names) else ("every study" if args.all else "as named")
    print(f"== {len(tasks)} studies ({kind}), {args.jobs} side by side: estimated {hms(total)} "
          f"({hms(serial)} one after another; from results/timings.csv)", flush=True)
    for t in tasks:
        note = "" if measured[t.name] else (" (quick case: estimate)" if t.quick else " (never timed: estimate)")
        print(f"   {t.name:28s} {'quick' if t.quick else 'full':5s} ~{hms(est[t.name]):>8s}{note}"
              f"{'  alone' if t.alone else ''}", flush=True)
    if args.list:
        return 0

    lock, cond = threading.Lock(), threading.Condition()
    state = {"running": {}, "done": {}, "failed": {}}
    start = time.monotonic()
    names = {t.name for t in tasks}
    pending = sorted(tasks, key=lambda t: -est[t.name])

    def remaining_estimate():
        left = sum(est[t.name] for t in pending) + sum(
            max(0.0, est[n] - (time.monotonic() - s)) for n, s in state["running"].items())
        return left / args.jobs

    def worker(task, load):
        t0 = time.monotonic()
        try:
            error = task.run()
        except Exception as e:  # a study that cannot start (missing binary) is a failure of that study
            error = str(e)
        wall = time.monotonic() - t0
        with cond:
            del state["running"][task.name]
            (state["failed"] if error else state["done"])[task.name] = (wall, error)
            if not error and not task.quick:
                save_timing(task.name, wall, args.jobs, load, lock)
            finished = len(state["done"]) + len(state["failed"])
            status = "done" if not error else f"FAILED ({error}; log {os.path.relpath(task.log, ROOT)})"
            print(f"[{finished}/{len(tasks)}] {task.name} {status} in {hms(wall)} (est. {hms(est[task.name])}); "
                  f"elapsed {hms(time.monotonic() - start)}, remaining ~{hms(remaining_estimate())}", flush=True)
            cond.notify_all()

    with cond:
        while pending or state["running"]:
            finished = set(state["done"]) | set(state["failed"])
            started = False
            for t in list(pending):
                if any(d in names and d not in finished for d in t.after):
                    continue
                if any(d in state["failed"] for d in t.after):
                    pending.remove(t)
                    state["failed"][t.name] = (0.0, "skipped: a study it reads failed")
                    started = True
                    continue
                busy = len(state["running"])
                alone_running = any(next(x for x in tasks if x.name == n).alone for n in state["running"])
                if busy >= args.jobs or alone_running or (t.alone and busy):
                    break
                pending.remove(t)
                state["running"][t.name] = time.monotonic()
                print(f"   start {t.name}{' (quick)' if t.quick else ''}", flush=True)
                threading.Thread(target=worker, args=(t, load_average()), daemon=True).start()
                started = True
            if not started and not state["running"]:
                sys.exit("run_studies: no study can start (the after= order has a cycle)")
            if not started:
                cond.wait()

    if not all(t.quick for t in tasks) and os.path.exists(os.path.join(ROOT, "scripts", "results_map.py")):
        subprocess.run([PYTHON, os.path.join(ROOT, "scripts", "results_map.py")], cwd=ROOT, check=False)
    print(f"== {len(state['done'])} of {len(tasks)} studies done in {hms(time.monotonic() - start)}", flush=True)
    quick_dirs = sorted({os.path.relpath(t.out, ROOT) for t in tasks if t.quick and t.name in state["done"]})
    if quick_dirs:
        print("   quick cases (not committed results): " + ", ".join(quick_dirs), flush=True)
    for name, (_, error) in state["failed"].items():
        print(f"   FAILED {name}: {error}", file=sys.stderr, flush=True)
    return 1 if state["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
