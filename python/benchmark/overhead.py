"""What the Python call adds over the library call: gearimpact.simulate(1)
against the same simulate() in C++ (simulate_case1.cpp). The least processor
time of the runs: the machine is shared, and wall time counts the others' work.
The C++ figures come on standard input, so that the two are timed one after the
other and never side by side:

    cmake --build build --target gearimpact_python_overhead
    build/bin/gearimpact_python_overhead 21 |
        PYTHONPATH=build/python /usr/bin/python3 python/benchmark/overhead.py 21

Not a test: no timing is asserted anywhere; this prints the figures.
"""

import json
import sys
import time

import gearimpact


def fastest_seconds(repeats, keep_series):
    seconds = []
    for _ in range(repeats):
        start = time.process_time()
        gearimpact.simulate(1, keep_series=keep_series)
        seconds.append(time.process_time() - start)
    return min(seconds)


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 21
    cpp = json.load(sys.stdin)
    python = {"series": fastest_seconds(repeats, True), "summary_only": fastest_seconds(repeats, False)}
    print(f"case 1 (300,000 RK4 steps), least processor time of {repeats} runs")
    print(f"{'':<22}{'C++ (s)':>10}{'Python (s)':>12}{'added (ms)':>12}")
    for key, label in (("summary_only", "summary only"), ("series", "with the series")):
        added_ms = (python[key] - cpp[key]) * 1e3
        print(f"{label:<22}{cpp[key]:>10.4f}{python[key]:>12.4f}{added_ms:>12.2f}")


if __name__ == "__main__":
    main()
