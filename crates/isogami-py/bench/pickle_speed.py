"""Unpickling speed of computed results (issue 42 item 19: they pickle as their data, so
unpickling computes nothing) and a 2-worker process pool against serial deployments.

    python crates/isogami-py/bench/pickle_speed.py

Prints each result's pickle size and its best unpickling time over 20 runs (ms and ms/MB),
and 12 deployments serially and through ProcessPoolExecutor(2) (results checked equal).
"""

import isogami, pickle, time
from concurrent.futures import ProcessPoolExecutor
def t(f, n=20):
    best = 1e9
    for _ in range(n):
        s = time.perf_counter(); f(); best = min(best, time.perf_counter() - s)
    return best
pull = isogami.pull_sheet("rotating-squares", "6x6")
run = isogami.deploy_sheet("rotating-squares", "6x6")
dep = isogami.deploy("rotating-squares")
for name, obj in [("SheetPull 6x6", pull), ("SheetDeployment 6x6", run), ("Deployment", dep)]:
    data = pickle.dumps(obj)
    sec = t(lambda: pickle.loads(data))
    print(f"{name}: {len(data)/1e6:.3f} MB, loads {sec*1e3:.2f} ms = {sec*1e3/(len(data)/1e6):.2f} ms/MB")
designs = [isogami.SAMPLE_OPENING_DESIGNS[i % len(isogami.SAMPLE_OPENING_DESIGNS)] for i in range(12)]
if __name__ == "__main__":
    s = time.perf_counter(); serial = [isogami.deploy(d) for d in designs]; a = time.perf_counter() - s
    with ProcessPoolExecutor(2) as pool:
        list(pool.map(isogami.deploy, designs[:2]))
        s = time.perf_counter(); par = list(pool.map(isogami.deploy, designs)); b = time.perf_counter() - s
    assert par == serial
    print(f"12 deployments: serial {a:.2f} s, 2-worker pool {b:.2f} s")
