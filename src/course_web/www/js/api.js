// The server's JSON questions (the page asks only /api/plot, when the student asks for a plot;
// what changes by itself comes on the websocket, see bridge.js's watchLab): answers, or an Error
// carrying the server's one-line reason.
export async function ask(question, params = {}) {
  const query = new URLSearchParams(params);
  const token = new URLSearchParams(window.location.search).get('token');
  if (token) query.set('token', token);
  // Relative to the page: the same server at / and behind a proxy's prefix (JupyterLab's /roslab/).
  const url = new URL('api/' + question + (query.toString() ? '?' + query : ''), window.location.href);
  const reply = await fetch(url, {cache: 'no-store'});
  const answer = await reply.json().catch(() => ({error: 'the server answered ' + reply.status}));
  if (!reply.ok || answer.error) throw new Error(answer.error || ('the server answered ' + reply.status));
  return answer;
}

// Calls `onHidden` when the page goes out of sight (another tab, a minimised window) and `onShown`
// when it comes back: a stream nobody sees is not worth its server's and its turtlesim's work.
export function whenHidden(onHidden, onShown) {
  document.addEventListener('visibilitychange', () => (document.hidden ? onHidden() : onShown()));
}
