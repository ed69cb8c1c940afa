// Test helper: the words of a POSIX command line as a shell splits it (bare words,
// single-quoted parts and backslash escapes: what the pages write). Not a test file itself.

/** Words of `line`. */
export function shellSplit(line) {
  const words = [];
  let word = null;
  for (let i = 0; i < line.length; i += 1) {
    const c = line[i];
    if (c === "'") {
      const end = line.indexOf("'", i + 1);
      word = (word ?? '') + line.slice(i + 1, end);
      i = end;
    } else if (c === '\\') {
      word = (word ?? '') + line[i + 1];
      i += 1;
    } else if (c === ' ') {
      if (word !== null) words.push(word);
      word = null;
    } else word = (word ?? '') + c;
  }
  if (word !== null) words.push(word);
  return words;
}
