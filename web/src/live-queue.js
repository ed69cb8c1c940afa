// Live design's request throttle (issue 24 item 7): while a slider is dragged the page asks
// the server for a deployment at most once per interval, always for the latest value (older
// values waiting are dropped), and a new request aborts the one in flight. The interval
// adapts to the server: at least `minInterval` ms and 1.5 × the typical answer time, where an
// aborted request counts as at least as slow as it had been when aborted — so a slow design
// stretches the interval until its answers get through instead of being aborted forever.
// The first value after a pause is sent at once. Pure logic (timers and clock injected), no DOM.

export class LatestThrottle {
  /**
   * `send(value, signal)` returns a promise of the answer; `onResult(answer, value, ms)` is
   * called for the answer of the latest sent value only (ms: from when the value was pushed),
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
    const wait = this.lastSent + this.interval() - this.now();
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
        this.onResult(result, value, done - at);
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
