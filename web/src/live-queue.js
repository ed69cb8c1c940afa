// Live design's request throttle (issue 24 item 7): while a slider is dragged the page asks
// the server for one deployment at a time, always for the latest value (older values waiting
// are dropped): a value is sent at once when nothing is in flight, else as soon as the
// answer in flight comes, or — when that takes longer than the interval — at the end of the
// interval, aborting the request in flight. The interval
// adapts to the server: at least `minInterval` ms and 1.5 × the typical answer time, where an
// aborted request counts as at least as slow as it had been when aborted — so a slow design
// stretches the interval until its answers get through instead of being aborted forever.
// The first value after a pause is sent at once. Pure logic (timers and clock injected), no DOM.

export class LatestThrottle {
  /**
   * `send(value, signal)` returns a promise of the answer; `onResult(answer, value, ms,
   * requestMs)` is called for the answer of the latest sent value only (ms: from when the
   * value was pushed; requestMs: from when it was sent),
   * `onError(error, value)` for its failure (never for an aborted request).
   */
  constructor(send, { onResult, onError, minInterval = 40, now = () => performance.now(), setTimer = (f, ms) => setTimeout(f, ms), clearTimer = (t) => clearTimeout(t) }) {
    this.send = send;
    this.onResult = onResult;
    this.onError = onError;
    this.minInterval = minInterval;
    this.now = now;
    this.setTimer = setTimer;
    this.clearTimer = clearTimer;
    this.pending = null; // {value, at}
    this.timer = null;
    this.inflight = null; // {controller, value, sent, at}
    this.lastSent = -Infinity;
    this.typical = 0; // ms
    this.sent = 0;
    this.aborted = 0;
  }

  /** The current interval between two requests, ms. */
  interval() {
    return Math.max(this.minInterval, 1.5 * this.typical);
  }

  /** True while a request is in flight or a value waits. */
  busy() {
    return Boolean(this.inflight || this.pending || this.timer);
  }

  /** Asks for `value`; it replaces any value still waiting. */
  push(value) {
    this.pending = { value, at: this.now() };
    if (this.timer !== null) return;
    // Nothing in flight: at once. Otherwise when the answer comes (see fire), or at the end
    // of the interval, aborting a request that is slower than the interval.
    const wait = this.inflight ? this.lastSent + this.interval() - this.now() : 0;
    if (wait <= 0) this.fire();
    else this.timer = this.setTimer(() => this.fire(), wait);
  }

  /** Drops the waiting value and aborts the request in flight. */
  cancel() {
    this.pending = null;
    if (this.timer !== null) this.clearTimer(this.timer);
    this.timer = null;
    if (this.inflight) {
      this.inflight.controller.abort();
      this.inflight = null;
    }
  }

  fire() {
    this.timer = null;
    if (!this.pending) return;
    const { value, at } = this.pending;
    this.pending = null;
    const t = this.now();
    if (this.inflight) {
      this.typical = Math.max(this.typical, t - this.inflight.sent);
      this.inflight.controller.abort();
      this.aborted += 1;
    }
    const controller = new AbortController();
    const mine = { controller, value, sent: t, at };
    this.inflight = mine;
    this.lastSent = t;
    this.sent += 1;
    let answer;
    try {
      answer = Promise.resolve(this.send(value, controller.signal));
    } catch (e) {
      answer = Promise.reject(e);
    }
    answer.then(
      (result) => {
        if (this.inflight !== mine) return;
        this.inflight = null;
        const done = this.now();
        this.typical = this.typical === 0 ? done - t : 0.7 * this.typical + 0.3 * (done - t);
        this.onResult(result, value, done - at, done - t);
        // A value that waited for this answer goes now.
        if (this.pending && this.timer !== null) {
          this.clearTimer(this.timer);
          this.fire();
        }
      },
      (e) => {
        if (this.inflight !== mine) return;
        this.inflight = null;
        if (e && e.name === 'AbortError') return;
        this.onError(e, value);
      },
    );
  }
}
