import { test } from 'node:test';
import assert from 'node:assert/strict';
import { FollowQueue, pinnedSet, shapeStatusText, shouldFollow } from '../src/shape.js';

const special = { class: 'special', constraints: [[0, 0, -0.7, 0.7]], pinned: [] };
const pinned = { class: 'special', constraints: [[1]], pinned: [0] };
const generic = { class: 'generic', constraints: [], pinned: [] };

test('status words name the class and the number of constraints', () => {
  assert.match(shapeStatusText(special), /^special: .* on 1 shape constraint; the sliders follow it$/);
  assert.match(shapeStatusText({ ...special, constraints: [[1], [2]] }), /2 shape constraints; the sliders follow them/);
  assert.match(shapeStatusText(special, { free: true }), /breaks the motion/);
  assert.match(shapeStatusText(generic), /^generic/);
  assert.equal(shapeStatusText(null), '');
  assert.equal(shapeStatusText({ class: 'fixed_shape', constraints: [], pinned: [] }), '');
  assert.equal(shapeStatusText({ error: 'not 1 DOF' }), 'shape analysis: not 1 DOF');
});

test('only a special design followed pins and follows', () => {
  assert.deepEqual([...pinnedSet(pinned)], [0]);
  assert.deepEqual([...pinnedSet(pinned, { free: true })], []);
  assert.deepEqual([...pinnedSet(generic)], []);
  assert.equal(shouldFollow(special), true);
  assert.equal(shouldFollow(special, { free: true }), false);
  assert.equal(shouldFollow(generic), false);
  assert.equal(shouldFollow(null), false);
});

/** A send whose answers the test releases one by one. */
function controlledSend() {
  const calls = [];
  const send = (index, value) => new Promise((resolve, reject) => calls.push({ index, value, resolve, reject }));
  return { calls, send };
}

test('moves while a request runs are coalesced to the latest, sent after it', async () => {
  const { calls, send } = controlledSend();
  const answers = [];
  const q = new FollowQueue(send, { onAnswer: (a) => answers.push(a), onError: () => assert.fail('no error') });
  const done = q.move(2, 0.23);
  q.move(2, 0.231);
  q.move(2, 0.232);
  q.move(3, 0.5);
  assert.equal(calls.length, 1);
  assert.equal(q.busy(), true);
  calls[0].resolve('first');
  await new Promise((r) => setTimeout(r, 0));
  assert.equal(calls.length, 2, 'the latest move goes next');
  assert.deepEqual([calls[1].index, calls[1].value], [3, 0.5]);
  calls[1].resolve('second');
  await done;
  assert.deepEqual(answers, ['first', 'second']);
  assert.equal(q.busy(), false);
});

test('an error is reported with its index and the queue goes on', async () => {
  const { calls, send } = controlledSend();
  const seen = [];
  const q = new FollowQueue(send, {
    onAnswer: (a) => seen.push(['answer', a]),
    onError: (e, i) => seen.push(['error', e.message, i]),
  });
  const done = q.move(0, 1);
  q.move(1, 2);
  calls[0].reject(new Error('pinned'));
  await new Promise((r) => setTimeout(r, 0));
  calls[1].resolve('ok');
  await done;
  assert.deepEqual(seen, [['error', 'pinned', 0], ['answer', 'ok']]);
  // clear() drops a waiting move.
  const again = q.move(0, 3);
  q.move(0, 4);
  q.clear();
  calls[2].resolve('only');
  await again;
  assert.equal(calls.length, 3);
});
