#!/usr/bin/python3
"""Markdown tables from the Google Benchmark JSON of the two suites (bench/).

    gbench_to_md.py --opencl gbench-opencl.json --reference gbench-reference.json \
        [--command "how they were made"] [--seconds N] > gbench.md

Reads the median aggregates (--benchmark_repetitions with
--benchmark_report_aggregates_only), pairs an OpenCL benchmark with the reference one of
the same name and arguments, and writes a summary at the default parameters, then one
table per kernel. Standard library only.
"""
import argparse
import json
import re

COUNTERS = ("pixels/s", "evals/s", "GFLOP/s", "GB/s")
TIME_SUFFIX = re.compile(r"/(manual|real)_time$")
# The summary's row of each kernel: the defaults of tests/stereo/kernel_cases.h at 320x240
# (the whole matcher only runs at 160x120).
SUMMARY_ARGS = ("width:320", "ndisp:64", "window:35")
SUMMARY_FALLBACK_WIDTH = "width:160"


def load_medians(path):
    """(context, {benchmark name without its time suffix: median entry}) in file order.

    Each median entry gets "cv", the coefficient of variation of the repetitions' times
    (None without repetitions)."""
    if not path:
        return {}, {}
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    medians = {}
    spreads = {}
    for entry in data.get("benchmarks", []):
        name = TIME_SUFFIX.sub("", entry["run_name"])
        aggregate = entry.get("aggregate_name")
        if aggregate == "cv":
            spreads[name] = entry["real_time"]  # a fraction, whatever the time unit
        elif entry.get("run_type") != "aggregate" or aggregate == "median":
            # A run without repetitions has no aggregates: its single result stands in.
            medians[name] = dict(entry, cv=None)
    for name, cv in spreads.items():
        if name in medians:
            medians[name]["cv"] = cv
    return data.get("context", {}), medians


def milliseconds(entry):
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[entry["time_unit"]]
    return entry["real_time"] * scale


def format_time(ms):
    if ms >= 1000:
        return f"{ms / 1000:.2f} s"
    if ms >= 1:
        return f"{ms:.2f} ms"
    return f"{ms * 1000:.1f} µs"


def format_rate(value):
    if value is None:
        return ""
    for scale, suffix in ((1e9, "G"), (1e6, "M"), (1e3, "k")):
        if abs(value) >= scale:
            return f"{value / scale:.3g}{suffix}"
    return f"{value:.3g}"


def split_name(name):
    """'propagate_spatial/width:320/ndisp:64/window:35' -> kernel, {arg: value}."""
    kernel, *args = name.split("/")
    return kernel, dict(arg.split(":", 1) for arg in args if ":" in arg)


def args_cell(entry, args):
    size = entry.get("label") or (args.get("width", "") and f"width {args['width']}")
    return [size, args.get("ndisp", ""), args.get("window", "")]


def format_cv(entry):
    return "" if entry.get("cv") is None else f"{100 * entry['cv']:.1f}%"


def row(path, entry, args, speedup):
    cells = args_cell(entry, args) + [path, format_time(milliseconds(entry)), format_cv(entry)]
    cells += [format_rate(entry.get(counter)) for counter in COUNTERS]
    cells.append(speedup)
    return "| " + " | ".join(cells) + " |"


def speedup_text(opencl, reference):
    if not opencl or not reference:
        return "—"
    return f"{milliseconds(reference) / milliseconds(opencl):.2f}x"


def kernel_order(opencl, reference):
    """Kernels in registration order (the suites register them in pipeline order; the
    file order is random when repetitions are interleaved): the OpenCL suite's, then
    those only the reference suite has."""
    order = []
    for suite in (opencl, reference):
        firsts = {}
        for name, entry in suite.items():
            kernel = split_name(name)[0]
            firsts[kernel] = min(firsts.get(kernel, entry["family_index"]), entry["family_index"])
        order += [k for k in sorted(firsts, key=firsts.get) if k not in order]
    return order


def summary_name(kernel, names):
    for width in (SUMMARY_ARGS[0], SUMMARY_FALLBACK_WIDTH):
        wanted = "/".join((kernel, width) + SUMMARY_ARGS[1:])
        if wanted in names:
            return wanted
    return None


def machine_lines(context, key_label):
    lines = []
    for key, label in key_label:
        if key in context:
            lines.append(f"- {label}: {context[key]}")
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--opencl", help="JSON of flexsight_bench_opencl")
    parser.add_argument("--reference", help="JSON of flexsight_bench")
    parser.add_argument("--command", default="scripts/stereo/run_gbench.sh")
    parser.add_argument("--seconds", type=int, help="wall time of both suites")
    options = parser.parse_args()

    opencl_context, opencl = load_medians(options.opencl)
    reference_context, reference = load_medians(options.reference)
    context = {**reference_context, **opencl_context}
    names = set(opencl) | set(reference)

    out = ["# Google Benchmark: OpenCL kernels and their reference", ""]
    took = f" in {options.seconds} s (both suites, building excluded)" if options.seconds else ""
    out.append(f"Made by `{options.command}`{took}; {context.get('date', '')}. "
               "Each time is the median of the repetitions.")
    out.append("")
    out += machine_lines(context, (
        ("num_cpus", "CPU cores"),
        ("mhz_per_cpu", "MHz per core"),
        ("opencl_device", "OpenCL device"),
        ("opencl_driver", "OpenCL driver"),
        ("reference_threads", "reference threads (OpenMP)"),
        ("load_avg", "load average at the start (a shared machine: expect a few % noise)"),
    ))
    if context.get("library_build_type") == "debug":
        out.append("- Google Benchmark says its library was built as debug (Debian's "
                   "package): that concerns its own bookkeeping; the times here are manual "
                   "(OpenCL profiling events, or the wall clock around the reference call).")
    out += ["", "How to read it:", "",
            "- OpenCL time: the device time of the stage's kernels, from their OpenCL "
            "profiling events; reference time: the wall clock of the reference function on "
            "every core. Uploads and the resetting of inputs between iterations count in "
            "neither.",
            "- Checkerboard stages (propagate_*, refine_random) run both parities of one "
            "view, so every pixel once. Inputs are those of the byte-for-byte tests "
            "(tests/stereo/kernel_cases.h).",
            "- evals/s: plane-candidate cost evaluations per second (nominal candidates). "
            "GFLOP/s and GB/s come from the work model of bench/stereo/kernel_work_model.h (57 "
            "flops and 76 requested load bytes per window sample); for the stages with the "
            "early exit (propagate_*, refine_random, the matchers) they are "
            "window-equivalent rates, an upper bound of the arithmetic done.",
            "- OpenCL speed-up: reference time / OpenCL time for the same arguments; cv: "
            "the spread of the repetitions (standard deviation / mean of their times).",
            "- Both paths use every core, so other work on the machine during a run makes "
            "the path it overlaps look up to twice as slow, often with a small cv (the "
            "repetitions are interleaved but close together): rerun on an idle machine "
            "before reading much into a ratio.",
            ""]

    out += ["## Summary at 320x240, ndisp 64, window 35 (the matchers at 160x120)", "",
            "| kernel | OpenCL | reference | OpenCL speed-up | OpenCL GFLOP/s | OpenCL GB/s |",
            "|---|---:|---:|---:|---:|---:|"]
    for kernel in kernel_order(opencl, reference):
        name = summary_name(kernel, names)
        if name is None:
            continue
        o, r = opencl.get(name), reference.get(name)
        out.append("| " + " | ".join([
            kernel,
            format_time(milliseconds(o)) if o else "—",
            format_time(milliseconds(r)) if r else "—",
            speedup_text(o, r),
            format_rate(o.get("GFLOP/s")) if o else "",
            format_rate(o.get("GB/s")) if o else "",
        ]) + " |")
    out.append("")

    header = ("| size | ndisp | window | path | median time | cv | pixels/s | evals/s "
              "| GFLOP/s | GB/s | OpenCL speed-up |")
    align = "|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|"
    for kernel in kernel_order(opencl, reference):
        out += [f"## {kernel}", "", header, align]
        for name in sorted((n for n in names if split_name(n)[0] == kernel),
                           key=lambda n: [int(v) for v in split_name(n)[1].values()
                                          if v.isdigit()]):
            args = split_name(name)[1]
            o, r = opencl.get(name), reference.get(name)
            if o:
                out.append(row("OpenCL", o, args, speedup_text(o, r)))
            if r:
                out.append(row("reference", r, args, ""))
        walls = [(opencl[n].get("label", n), opencl[n]["wall_ms"]) for n in opencl
                 if split_name(n)[0] == kernel and "wall_ms" in opencl[n]]
        if walls:
            out += ["", "OpenCL wall clock of a run (the host's view: uploads, launches, "
                    "waits and reads included): "
                    + ", ".join(f"{size} {format_time(ms)}" for size, ms in walls) + "."]
        out.append("")
    print("\n".join(out))


if __name__ == "__main__":
    main()
