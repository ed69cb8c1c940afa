// The live-design throttle (live-queue.js) on a fake clock: a drag's values are sent at most
// once per interval, the latest wins, a new request aborts the one in flight, answers of
// aborted requests are never shown, and a slow server stretches the interval until its
// answers get through.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { LatestThrottle } from '../src/live-queue.js';

/** A fake clock with timers, and a server whose answers the test releases by hand. */
function rig({ minInterval = 40 } = {}) {
  let now = 0;
  let timers = [];
  const requests = [];
  const shown = [];
  const errors = [];
  const q = new LatestThrottle(
    (value, signal) =>
      new Promise((ok, fail) => {
        const r = { value, signal, ok, fail };
        signal.addEventListener('abort', () => fail(Object.assign(new Error('aborted'), { name: 'AbortError' })));
        requests.push(r);
      }),
    {
      minInterval,
      onResult: (answer, value, ms) => shown.push({ answer, value, ms }),
      onError: (e, value) => errors.push({ e, value }),
      now: () => now,
      setTimer: (f, ms) => {
        const t = { f, at: now + ms };
        timers.push(t);
        return t;
      },
      clearTimer: (t) => {
        timers = timers.filter((x) => x !== t);
      },
    },
  );
  const advance = async (ms) => {
    const end = now + ms;
    for (;;) {
      timers.sort((a, b) => a.at - b.at);
      const t = timers[0];
      if (!t || t.at > end) break;
      timers.shift();
      now = t.at;
      t.f();
      await Promise.resolve();
    }
    now = end;
    await new Promise((r) => setImmediate(r));
  };
  return { q, requests, shown, errors, advance };
}

test('the first value goes at once; a drag sends at most one request per interval, the latest value', async () => {
  const { q, requests, advance } = rig();
  q.push(1);
  assert.deepEqual(requests.map((r) => r.value), [1], 'leading edge: sent at once');
  requests[0].ok('a1');
  await advance(0);
  for (let v = 2; v <= 10; v += 1) {
    q.push(v);
    await advance(10); // input every 10 ms
  }
  await advance(100);
  const values = requests.map((r) => r.value);
  // 90 ms of dragging at a 40 ms interval: at most 4 requests in all, the last one for 10.
  assert.ok(values.length <= 4, `${values}`);
  assert.equal(values.at(-1), 10, 'the latest value wins');
  for (let i = 1; i < values.length; i += 1) assert.ok(values[i] > values[i - 1], 'never an older value');
});

test('a new request aborts the one in flight, whose answer is never shown', async () => {
  const { q, requests, shown, advance } = rig();
  q.push(1);
  await advance(50);
  q.push(2); // interval passed: sent at once, aborting 1
  assert.equal(requests.length, 2);
  assert.ok(requests[0].signal.aborted, 'the request in flight was aborted');
  requests[0].ok('late answer for 1'); // a server that answers anyway
  requests[1].ok('answer for 2');
  await advance(0);
  assert.deepEqual(shown.map((s) => s.answer), ['answer for 2']);
});

test('answers arriving during a drag are drawn, so the page redraws while the hand moves', async () => {
  const { q, requests, shown, advance } = rig();
  let answered = 0;
  for (let step = 0; step < 100; step += 1) {
    q.push(step);
    // The server answers every request 20 ms after it was sent.
    for (const r of requests) {
      if (!r.done && !r.signal.aborted && (r.sentAt ??= step) <= step - 2) {
        r.done = true;
        r.ok(`answer ${r.value}`);
        answered += 1;
      }
    }
    await advance(10);
  }
  assert.ok(shown.length >= 10, `redraws during a 1 s drag: ${shown.length} (answered ${answered})`);
});

test('a slow server stretches the interval instead of being aborted forever', async () => {
  const { q, requests, shown, advance } = rig();
  // Every request takes 300 ms.
  for (let step = 0; step < 300; step += 1) {
    q.push(step);
    for (const r of requests) {
      r.sentAt ??= step;
      if (!r.done && !r.signal.aborted && step - r.sentAt >= 30) {
        r.done = true;
        r.ok(r.value);
      }
    }
    await advance(10);
  }
  assert.ok(shown.length >= 3, `answers shown in 3 s against a 300 ms server: ${shown.length}`);
  assert.ok(q.interval() >= 300, `interval ${q.interval()}`);
});

test('a refusal reaches onError; an aborted request does not', async () => {
  const { q, requests, errors, advance } = rig();
  q.push('bad');
  requests[0].fail(Object.assign(new Error('ill-shaped'), { kind: 'ill_shaped' }));
  await advance(0);
  assert.equal(errors.length, 1);
  assert.equal(errors[0].value, 'bad');
  q.push('x');
  q.cancel();
  await advance(100);
  assert.equal(errors.length, 1, 'cancelled: no error');
});

test('a value that waits for the answer in flight is sent as soon as that answer comes', async () => {
  const { q, requests, shown, advance } = rig({ minInterval: 40 });
  q.push(1);
  await advance(5);
  q.push(2); // 1 in flight: 2 waits
  assert.equal(requests.length, 1);
  await advance(5);
  requests[0].ok('answer 1'); // at 10 ms, long before the interval ends
  await advance(0);
  assert.deepEqual(shown.map((s) => s.answer), ['answer 1']);
  assert.deepEqual(requests.map((r) => r.value), [1, 2], '2 sent when 1 answered, not at 40 ms');
  assert.ok(!requests[0].signal.aborted);
});
