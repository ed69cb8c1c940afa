// Shape-aware sliders (issue 13, item 6): the words for a design's shape class, which
// sliders are pinned, and the queue that turns a dragged slider into follow requests.
// A special design keeps one degree of freedom only on a sub-manifold of shapes, so a slider
// that moves one parameter alone breaks it; the server's POST /api/shape/follow moves the
// others along that sub-manifold. Pure logic, no DOM: the editor draws it.

/** One-line description of a classification (`GET /api/shape`), or '' when there is
 * nothing to say (a family without shape parameters). */
export function shapeStatusText(info, { free = false } = {}) {
  if (!info) return '';
  if (info.error) return `shape analysis: ${info.error}`;
  if (info.class === 'generic') return 'generic: every nearby shape moves, each slider moves alone';
  if (info.class === 'special') {
    const n = info.constraints.length;
    const what = `special: one degree of freedom only on ${n} shape constraint${n === 1 ? '' : 's'}`;
    return free
      ? `${what}; moving freely: a slider now moves alone and breaks the motion`
      : `${what}; the sliders follow ${n === 1 ? 'it' : 'them'}`;
  }
  return '';
}

/** Parameters a slider cannot move while the design keeps moving (none when moving freely
 * or for a design that is not special). */
export function pinnedSet(info, { free = false } = {}) {
  if (!info || free || info.class !== 'special') return new Set();
  return new Set(info.pinned || []);
}

/** Whether a slider move of this design should be followed on the server. */
export function shouldFollow(info, { free = false } = {}) {
  return Boolean(info && !free && info.class === 'special');
}

/**
 * Coalesces slider moves into follow requests: at most one request is in flight; while it
 * runs only the latest move is kept, and it is sent next, starting from the design the
 * previous answer gave. `send(index, value)` returns a promise of the server's answer;
 * `onAnswer(answer)` and `onError(error, index)` are called in order, never for a move that
 * a later one replaced.
 */
export class FollowQueue {
  constructor(send, { onAnswer, onError }) {
    this.send = send;
    this.onAnswer = onAnswer;
    this.onError = onError;
    this.pending = null;
    this.running = null;
  }

  /** Asks for parameter `index` at `value`; returns a promise that settles when the queue
   * is empty again. */
  move(index, value) {
    this.pending = { index, value };
    if (!this.running) this.running = this.pump().finally(() => { this.running = null; });
    return this.running;
  }

  /** True while a request is in flight or waiting. */
  busy() {
    return Boolean(this.running || this.pending);
  }

  /** Forgets a waiting move (the in-flight answer is still delivered). */
  clear() {
    this.pending = null;
  }

  async pump() {
    while (this.pending) {
      const { index, value } = this.pending;
      this.pending = null;
      try {
        const answer = await this.send(index, value);
        this.onAnswer(answer, index);
      } catch (e) {
        this.onError(e, index);
      }
    }
  }
}
