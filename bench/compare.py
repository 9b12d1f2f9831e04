"""bench/compare's driver: runs W1-W5 in dqsym and in the installed peers and prints one table
(markdown) followed by the performance targets, met or missed. Called by bench/compare, which
builds and installs what it needs; see that script for the options."""

import argparse
import json
import os
import platform
import re
import signal
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

WORKLOADS = {
    "W1": "planar RRR end effector (px, py)",
    "W2": "PUMA 560 pose in closed form (4x4 rows 0-2 and DQ)",
    "W3": "generic 6R, every DH parameter symbolic, expanded (4x4 rows 0-2)",
    "W4": "PUMA 560 8x6 DQ Jacobian in closed form",
    "W5": "20-joint planar chain end effector (alpha = d = 0; a_i, theta_i symbolic)",
}


def descendants(pid):
    """The process ids below pid, deepest last, from /proc."""
    out = []
    try:
        with open(f"/proc/{pid}/task/{pid}/children") as f:
            kids = [int(x) for x in f.read().split()]
    except OSError:
        return out
    for k in kids:
        out.append(k)
        out.extend(descendants(k))
    return out


def run_limited(cmd, limit, env=None, keep_stderr=False):
    """Runs cmd under /usr/bin/time for its peak RSS. At `limit` seconds it kills what runs
    under time(1), not time(1) itself, so a killed process still reports its peak RSS.
    Returns (stdout lines, finished, peak RSS in MB or None, wall seconds[, stderr lines])."""
    with tempfile.NamedTemporaryFile("r", suffix=".rss") as rss:
        full = ["/usr/bin/time", "-f", "%M", "-o", rss.name] + cmd
        t = time.perf_counter()
        p = subprocess.Popen(
            full, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
            start_new_session=True, cwd=ROOT, env=env,
        )
        try:
            out, err = p.communicate(timeout=limit)
            finished = p.returncode == 0
        except subprocess.TimeoutExpired:
            for pid in reversed(descendants(p.pid)):
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
            try:
                out, err = p.communicate(timeout=30)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                out, err = p.communicate()
            finished = False
        wall = time.perf_counter() - t
        text = rss.read().strip().splitlines()
        kb = next((int(x) for x in reversed(text) if x.strip().isdigit()), None)
    if not finished and not keep_stderr and err.strip() and "Command terminated" not in err:
        sys.stderr.write(f"[{' '.join(cmd)}] {err.strip()[-500:]}\n")
    mb = kb / 1024 if kb else None
    if keep_stderr:
        return out.splitlines(), finished, mb, wall, err.splitlines()
    return out.splitlines(), finished, mb, wall


def parse_stage_lines(lines):
    return [json.loads(l) for l in lines if l.startswith("{")]


def maxima_stages(lines):
    """Turns the Maxima peer's STAGE/EXPR lines into stage records, counting operations with
    the same counter as the Python peers (the text is parsed by SymPy, outside the timing)."""
    import sympy
    from common import size  # noqa: E402  (bench/peers on sys.path)

    out, cur = [], None
    for l in lines:
        if l.startswith("STAGE "):
            _, name, secs = l.split()
            cur = {"stage": name, "seconds": float(secs), "exprs": []}
            out.append(cur)
        elif l.startswith("EXPR ") and cur is not None:
            cur["exprs"].append(l[5:])
    recs = []
    for c in out:
        exprs = [sympy.sympify(e.replace("%pi", "pi"), evaluate=False) for e in c["exprs"]]
        ops, calls = size(exprs)
        recs.append({"stage": c["stage"], "seconds": c["seconds"], "ops": ops,
                     "calls": calls, "entries": len(exprs)})
    return recs


def fmt_time(s):
    if s is None:
        return "-"
    if s < 1e-3:
        return f"{s * 1e6:.0f} µs"
    if s < 1:
        return f"{s * 1e3:.1f} ms"
    return f"{s:.2f} s"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--limit", type=float, default=120.0)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--workloads", default="W1,W2,W3,W4,W5")
    ap.add_argument("--peers", default="sympy,symengine,maxima,symplex")
    ap.add_argument("--python", required=True)
    ap.add_argument("--dqsym", required=True)
    ap.add_argument("--workloads-bin", required=True)
    ap.add_argument("--symplex-bin", default="")
    ap.add_argument("--maxima", default="")
    a = ap.parse_args()
    sys.path.insert(0, os.path.join(HERE, "peers"))
    wls = a.workloads.split(",")
    peers = a.peers.split(",")

    rows = []  # (workload, part, system, stage, seconds|None, ops, calls, rss, note)
    dq = {}  # (workload, part, "expand" | "closed form") -> record
    for w in wls:
        lines, ok, rss, _ = run_limited([a.workloads_bin, "--runs", str(a.runs), w], a.limit)
        for r in parse_stage_lines(lines):
            part = "4x4" if "(4x4)" in r["part"] else "DQ" if "(DQ)" in r["part"] else ""
            expand = r["part"].startswith("expand")
            kind = "expand" if expand else "closed form"
            r["rss"] = rss
            r["expand"] = expand
            dq[(w, part, kind)] = r
            note = r["error"] or ""
            sized = r["ops"] > 0
            if expand and not r["error"]:
                note = (f"{r['terms']} monomials in cos/sin (the peers' form)" if part == "4x4"
                        else f"{r['terms']} canonical terms (a Fourier series in half angles)")
            rows.append((w, part, "dqsym", kind,
                         None if r["error"] and expand else r["seconds"],
                         r["ops"] if sized else None, r["calls"] if sized else None, rss, note))
        if not ok and not lines:
            rows.append((w, "", "dqsym", "", None, None, None, rss, "did not finish"))

    # The 20-joint chain with every DH parameter symbolic: its expansion grows as k 4^k terms
    # (k links), so `dqsym fk` prints it exactly as a recurrence; timed as a whole process.
    full = None
    if "W5" in wls:
        chain20 = os.path.join(ROOT, "tests/data/chain20_symbolic.toml")
        lines, ok, rss, wall = run_limited([a.dqsym, "fk", chain20, "--jacobian"], a.limit)
        full = (ok, rss, wall, len(lines))

    # Whole processes: `dqsym fk` on the PUMA 560 file (W2) and with --jacobian (W4), and a
    # SymEngine script that imports SymEngine, expands the same products and prints them.
    def process_median(cmd, n):
        times = []
        for _ in range(n):
            t = time.perf_counter()
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, cwd=ROOT)
            times.append(time.perf_counter() - t)
        return statistics.median(times)

    proc = {}
    se_proc = {}
    robot = os.path.join(ROOT, "examples/robots/puma560.toml")
    have_symengine = "symengine" in peers and subprocess.run(
        [a.python, "-c", "import symengine"], capture_output=True).returncode == 0
    n_proc = max(a.runs, 5) * 4
    for w, extra in (("W2", []), ("W4", ["--jacobian"])):
        if w not in wls:
            continue
        proc[w] = process_median([a.dqsym, "fk", robot] + extra, n_proc)
        if have_symengine:
            se_proc[w] = process_median(
                [a.python, os.path.join(HERE, "peers/symengine_process.py"), w], max(a.runs, 5))

    available = {}
    cmds = {
        "sympy": lambda w: [a.python, os.path.join(HERE, "peers/sympy_peer.py"), w],
        "symengine": lambda w: [a.python, os.path.join(HERE, "peers/symengine_peer.py"), w],
        "symplex": lambda w: [a.symplex_bin, w],
        "maxima": lambda w: [a.maxima, "--very-quiet", "--batch-string",
                             f'W: "{w}"$ batchload("{os.path.join(HERE, "peers/maxima.mac")}")$'],
    }
    for p in peers:
        if p in ("sympy", "symengine"):
            ok = subprocess.run([a.python, "-c", f"import {p}"], capture_output=True).returncode == 0
            available[p] = ok or "not installed"
        elif p == "symplex":
            available[p] = (bool(a.symplex_bin) and os.path.exists(a.symplex_bin)) or "not built"
        elif p == "maxima":
            available[p] = bool(a.maxima) or "not installed (bench/compare --install-maxima)"

    peer_recs = {}  # (peer, workload) -> (records, finished)
    for p in peers:
        if available[p] is not True:
            rows.append(("all", "", p, "", None, None, None, None, available[p]))
            continue
        for w in wls:
            lines, ok, rss, _ = run_limited(cmds[p](w), a.limit)
            recs = maxima_stages(lines) if p == "maxima" else parse_stage_lines(lines)
            peer_recs[(p, w)] = (recs, ok)
            for r in recs:
                part, stage = (r["stage"].split(":") + [""])[:2] if ":" in r["stage"] else ("", r["stage"])
                part = {"matrix": "4x4", "dq": "DQ"}.get(part, part)
                rows.append((w, part, p, stage, r["seconds"], r["ops"], r["calls"], rss, ""))
            if not ok:
                rows.append((w, "~", p, "(next stage)", None, None, None, rss,
                             f"did not finish (limit {a.limit:.0f} s)"))

    # The table.
    def dq_time(w, part=None, kind=None):
        """dqsym's time on the same workload, part and kind of result (None when dqsym failed
        there); without a kind, the closed form when there is one."""
        recs = [r for (ww, pp, kk), r in dq.items()
                if ww == w and not r["error"] and (part is None or pp == part)
                and (kind is None or kk == kind)]
        recs.sort(key=lambda r: r["expand"])
        return recs[0]["seconds"] if recs else None

    order = {w: i for i, w in enumerate(wls)}
    rows.sort(key=lambda r: (order.get(r[0], -1), r[1], r[2] != "dqsym", r[2]))
    print("| workload | part | system | stage | time | + - * / and calls | trig/sqrt calls | time / dqsym | peak RSS | note |")
    print("|---|---|---|---|---:|---:|---:|---:|---:|---|")
    for w, part, sysname, stage, secs, ops, calls, rss, note in rows:
        part = "" if part == "~" else part
        # A peer's expansion is set against dqsym's expansion when dqsym has one in the same
        # form, a simplifier's result against dqsym's closed form.
        base = None
        if stage == "expand" and (w, part, "expand") in dq and dq[(w, part, "expand")]["ops"] > 0:
            base = dq_time(w, part, "expand")
        if base is None:
            base = dq_time(w, part, "closed form")
        ratio = "-"
        if secs is not None and base and sysname != "dqsym":
            ratio = f"{secs / base:,.0f}x" if secs / base >= 10 else f"{secs / base:.1f}x"
        elif sysname == "dqsym" and secs is not None and (stage != "expand" or ops is not None):
            ratio = "1"
        print(f"| {w} | {part} | {sysname} | {stage} | {fmt_time(secs) if secs is not None else 'did not finish' if 'did not' in note else '-'} "
              f"| {ops if ops is not None else '-'} | {calls if calls is not None else '-'} | {ratio} "
              f"| {f'{rss:.0f} MB' if rss else '-'} | {note} |")
    print()
    print("dqsym times are the median of %d in-process runs (W2: the 4x4 and the DQ together, so "
          "each part's ratio is conservative); peer times are one run from the start of the "
          "workload, excluding interpreter start-up; a simplifier's time includes the "
          "expansion before it." % a.runs)
    if full is not None:
        ok, rss, wall, n = full
        what = (f"printed its exact recurrence with the 8 x 20 Jacobian ({n} lines) in "
                f"{fmt_time(wall)}, peak RSS {rss or 0:.0f} MB" if ok
                else f"did not finish within {a.limit:.0f} s")
        print(f"\nW5 with every DH parameter symbolic (20 joints, 80 symbols; the expanded DQ "
              f"would have about 2e13 terms per component): `dqsym fk "
              f"tests/data/chain20_symbolic.toml --jacobian` {what} (whole process).")
    if proc:
        print("\nWhole process, median of %d runs: `dqsym fk examples/robots/puma560.toml` "
              "(W2) and with `--jacobian` (W4): " % n_proc
              + ", ".join(f"{w} {fmt_time(s)}" for w, s in proc.items()))
    if se_proc:
        print("SymEngine as a process (`bench/peers/symengine_process.py`: start Python, import "
              "SymEngine, expand the same products, print them; median of %d): " % max(a.runs, 5)
              + ", ".join(f"{w} {fmt_time(s)}" for w, s in se_proc.items()))

    # The targets.
    print("\n### Targets\n")

    def line(ok, text):
        print(f"- [{'met' if ok else 'MISSED'}] {text}")

    for w, lim in (("W2", 0.020), ("W4", 0.050)):
        s = dq_time(w)
        if s is not None:
            line(s <= lim, f"{w} <= {lim * 1e3:.0f} ms: {fmt_time(s)}")
    if ("W5", "", "closed form") in dq:
        r = dq[("W5", "", "closed form")]
        line(r["seconds"] <= 2 and (r["rss"] or 0) <= 200,
             f"W5 <= 2 s and peak RSS <= 200 MB: {fmt_time(r['seconds'])} (in process), {r['rss']:.0f} MB (peak RSS of the process)")
    if full is not None:
        ok, rss, wall, _ = full
        line(ok and wall <= 2 and (rss or 0) <= 200,
             f"W5 with every DH parameter symbolic, `dqsym fk --jacobian` <= 2 s and 200 MB: "
             f"{fmt_time(wall)}, {rss or 0:.0f} MB (whole process)")
    for w in ("W2", "W4"):
        if w in proc and w in se_proc:
            line(proc[w] <= se_proc[w] / 10,
                 f"{w} as a process ({fmt_time(proc[w])}) <= 1/10 of SymEngine expanding the "
                 f"same products as a process ({fmt_time(se_proc[w])}): "
                 f"{se_proc[w] / proc[w]:.1f}x")
        recs, _ = peer_recs.get(("symengine", w), ([], False))
        exp = sum(r["seconds"] for r in recs if r["stage"].endswith("expand"))
        if w in proc and recs:
            print(f"  (in-process, SymEngine's expansion alone takes {fmt_time(exp)}, "
                  f"{exp / proc[w]:.2f}x dqsym's whole process)")
    for w in wls:
        for (ww, part, kind), r in dq.items():
            # dqsym's most compact result for each part: the closed form, or an expansion
            # that is sized where there is no closed form.
            if ww != w or r["error"] or (r["expand"] and (r["ops"] == 0 or (w, part, "closed form") in dq)):
                continue
            best = None
            for p in peers:
                for pr in peer_recs.get((p, w), ([], False))[0]:
                    ppart = {"matrix": "4x4", "dq": "DQ"}.get(pr["stage"].split(":")[0], "") if ":" in pr["stage"] else ""
                    if ppart != part or pr["ops"] > r["ops"]:
                        continue
                    if best is None or pr["seconds"] < best[1]["seconds"]:
                        best = (p, pr)
            label = f"{w}{' ' + part if part else ''}{' (expanded)' if r['expand'] else ''}"
            if best is None:
                print(f"- [n/a] {label}: no peer reached a result as compact as dqsym's "
                      f"({r['ops']} ops) within the limit")
            else:
                p, pr = best
                ratio = pr["seconds"] / r["seconds"]
                line(ratio >= 100, f"{label}: >= 100x faster than the fastest equally compact peer "
                     f"({p} {pr['stage']}, {pr['ops']} ops, {fmt_time(pr['seconds'])}): {ratio:,.0f}x")

    # Expansion against expansion, where dqsym computes the peers' form.
    for (w, part, kind), r in dq.items():
        if kind != "expand" or r["error"] or r["ops"] == 0:
            continue
        best = None
        for p in peers:
            for pr in peer_recs.get((p, w), ([], False))[0]:
                if pr["stage"] == {"4x4": "matrix", "DQ": "dq"}.get(part, "") + ":expand":
                    if best is None or pr["seconds"] < best[1]["seconds"]:
                        best = (p, pr)
        if best:
            p, pr = best
            print(f"- [info] {w} {part} expansion ({r['ops']} ops in dqsym, {pr['ops']} in {p}): "
                  f"dqsym {fmt_time(r['seconds'])}, {p} {fmt_time(pr['seconds'])}: "
                  f"{pr['seconds'] / r['seconds']:.1f}x")

    cpu = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(l.split(":", 1)[1].strip() for l in f if l.startswith("model name"))
    except (OSError, StopIteration):
        pass
    print(f"\nMachine: {os.cpu_count()} cores ({cpu}), {platform.system()} {platform.release()}, "
          f"load average {os.getloadavg()[0]:.1f} at the end; {time.strftime('%Y-%m-%d')}.")


if __name__ == "__main__":
    main()
