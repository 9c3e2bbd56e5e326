"""HiGHS on the running-bond walls' static program, side by side with voussoir (issue 28).

The program is the one voussoir gives Clarabel (`statics::StaticProblem`, maximise lambda,
load toward +x), written as a free MPS file by the general-kinematic bench:

    VOUSSOIR_EXPORT_MPS=/tmp/wall1000.mps VOUSSOIR_BENCH_CHILD=export:1000 \
        target/release/deps/general_kinematic-<hash>

(`cargo bench --bench general_kinematic --no-run` prints the binary; 100, 1000 and 10000 give
the 105-, 1,008- and 10,050-block walls). Then, in a virtual environment with `highspy`
(`python3 -m venv /tmp/hvenv && /tmp/hvenv/bin/pip install highspy`):

    /tmp/hvenv/bin/python benches/highs_wall.py /tmp/wall1000.mps [--lambda 0.41670956618]

Each solver (dual simplex, primal simplex, interior point with and without crossover) runs in
a process of its own, so its peak resident set (VmHWM) is its own; the time is HiGHS's own
run time (reading the file left out) and the wall time of `run()`. The objective is -lambda;
`--lambda` compares HiGHS's optimum with voussoir's.
"""

import argparse
import json
import subprocess
import sys
import time


def peak_mib():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def child(path, solver, crossover, presolve):
    import highspy

    h = highspy.Highs()
    h.setOptionValue("output_flag", False)
    h.setOptionValue("threads", 1)
    h.setOptionValue("solver", "simplex" if solver.endswith("simplex") else "ipm")
    if solver == "dual simplex":
        h.setOptionValue("simplex_strategy", 1)
    elif solver == "primal simplex":
        h.setOptionValue("simplex_strategy", 4)
    else:
        h.setOptionValue("run_crossover", "on" if crossover else "off")
    h.setOptionValue("presolve", "on" if presolve else "off")
    # Tight tolerances, as voussoir's 1e-10.
    h.setOptionValue("primal_feasibility_tolerance", 1e-10)
    h.setOptionValue("dual_feasibility_tolerance", 1e-10)
    h.setOptionValue("ipm_optimality_tolerance", 1e-10)
    h.readModel(path)
    t = time.perf_counter()
    h.run()
    wall = time.perf_counter() - t
    info = h.getInfo()
    out = {
        "status": h.modelStatusToString(h.getModelStatus()),
        "lambda": -info.objective_function_value,
        "seconds": wall,
        "highs_seconds": h.getRunTime(),
        "simplex_iterations": info.simplex_iteration_count,
        "ipm_iterations": info.ipm_iteration_count,
        "peak_mib": peak_mib(),
    }
    print(json.dumps(out))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mps")
    ap.add_argument("--lambda", dest="lam", type=float, default=None)
    ap.add_argument("--child", default=None)
    ap.add_argument("--crossover", action="store_true")
    ap.add_argument("--no-presolve", action="store_true")
    ap.add_argument("--solvers", default="dual simplex,primal simplex,ipm,ipm+crossover")
    a = ap.parse_args()
    if a.child:
        child(a.mps, a.child, a.crossover, not a.no_presolve)
        return
    print(f"{'solver':<16} {'presolve':>8} {'status':>8} {'lambda':>16} {'s':>8} "
          f"{'iter':>7} {'MiB':>7} {'rel. diff':>10}")
    for name in a.solvers.split(","):
        solver, crossover = name, False
        if name == "ipm+crossover":
            solver, crossover = "ipm", True
        for presolve in (True, False):
            cmd = [sys.executable, __file__, a.mps, "--child", solver]
            if crossover:
                cmd.append("--crossover")
            if not presolve:
                cmd.append("--no-presolve")
            r = subprocess.run(cmd, capture_output=True, text=True)
            try:
                o = json.loads(r.stdout.strip().splitlines()[-1])
            except (IndexError, json.JSONDecodeError):
                print(name, "failed:", r.stdout[-500:], r.stderr[-500:])
                continue
            it = o["simplex_iterations"] if solver.endswith("simplex") else o["ipm_iterations"]
            diff = ""
            if a.lam is not None:
                diff = f"{abs(o['lambda'] - a.lam) / abs(a.lam):.1e}"
            print(f"{name:<16} {'on' if presolve else 'off':>8} {o['status'][:8]:>8} "
                  f"{o['lambda']:>16.12f} {o['seconds']:>8.3f} {it:>7} "
                  f"{o['peak_mib']:>7.1f} {diff:>10}", flush=True)


if __name__ == "__main__":
    main()
