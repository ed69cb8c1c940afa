#!/usr/bin/env python3
"""Folds `inferno-collapse-perf` stacks of an `isogami explore` run into the pipeline's stages.

Usage: fold.py STACKS.folded > STAGES.folded

Each stack is cut at the frame that names its stage: the topology enumeration (stages
mobility, separating and unique), or a catalogue characterisation, told apart by whether
`sample_shapes` is on the stack (stage shapes) or not (stage deploy_threshold). Frames of
rayon, the standard library and closures are dropped, generic arguments are cut, and a
function that recurs on one stack (rayon nests the same call) is kept once. Stacks that perf
could not unwind to a stage are counted under "stack not resolved".
"""
import collections
import re
import sys

NOISE = re.compile(
    r"^(catalog::part::run_unit_part|catalog::unit::sample_shapes|catalog::unit::characterise_all"
    r"|rayon|rayon_core|core::|std::|alloc::|\{closure|<core::|<alloc::|<rayon|<std|<&|__|_start"
    r"|main$|clone3|start_thread|crossbeam|call_|run_inline|join_context|join$|halt_unwinding"
    r"|catch_unwind|do_call|try|fold|helper|bridge|drive|with_producer|callback|consume|collect"
    r"|from_par_iter|reduce|next|map$|call$|execute|main_loop|wait_until|run$|\[unknown\]"
    r"|for_each|par_|\s)"
)
ENUMERATION = "explore::pipeline::enumerate_topology_part"
CHARACTERISE = "catalog::unit::characterise"


def name(frame):
    if "characterise_all::{closure" in frame:
        return CHARACTERISE
    frame = frame.replace(" (inlined)", "")
    frame = re.sub(r"<impl ([^>]*?)>::", "", frame)
    if "<" in frame and not frame.startswith("<"):
        frame = frame[: frame.index("<")]
    return re.sub(r"^isogami::", "", frame)


def stage_stack(stack):
    frames = [name(f) for f in stack.split(";")[1:]]
    frames = [f for f in frames if f and not NOISE.match(f) and "_[i]" not in f]
    if ENUMERATION in frames:
        head = "topology enumeration (stages mobility, separating, unique)"
        frames = [head] + frames[frames.index(ENUMERATION) + 1 :]
    elif CHARACTERISE in frames:
        if "sample_shapes" in stack:
            head = "stage shapes: shape samples deployed, finite figures"
        else:
            head = "stage deploy_threshold: default shapes deployed, finite figures"
        frames = [head] + frames[frames.index(CHARACTERISE) + 1 :]
    elif any(f.startswith("commands::") or "isogami_store" in f for f in frames):
        frames = ["store and command line"] + frames[-3:]
    else:
        frames = ["stack not resolved"] + frames[-2:]
    kept, seen = [], set()
    for f in frames:
        if f not in seen:
            seen.add(f)
            kept.append(f)
    return ";".join(kept)


def fail(message):
    print(message, file=sys.stderr)
    sys.exit(2)


def main():
    if len(sys.argv) != 2:
        fail("usage: fold.py STACKS.folded > STAGES.folded")
    totals = collections.Counter()
    try:
        with open(sys.argv[1]) as lines:
            for number, line in enumerate(lines, 1):
                stack, _, count = line.rstrip("\n").rpartition(" ")
                if not count.isdigit():
                    fail(f"fold.py: {sys.argv[1]}:{number}: not a folded stack (STACK COUNT)")
                totals[stage_stack(stack)] += int(count)
    except OSError as e:
        fail(f"fold.py: cannot read {sys.argv[1]}: {e.strerror}")
    for stack, count in sorted(totals.items()):
        print(stack, count)


if __name__ == "__main__":
    main()
