// The studio server's HTTP API (see StudioServer.cs). Commands answer { message } or, refused, { error } with 400.

export async function command(path, body) {
  const response = await fetch(`api/${path}`, {
    method: 'POST',
    headers: body instanceof ArrayBuffer ? { 'Content-Type': 'application/octet-stream' } : { 'Content-Type': 'application/json' },
    body: body instanceof ArrayBuffer ? body : JSON.stringify(body ?? {}),
  });
  let json = {};
  try { json = await response.json(); } catch { /* an empty or non-JSON answer */ }
  if (!response.ok) throw new Error(json.error ?? `${path}: HTTP ${response.status}`);
  return json.message ?? '';
}

export async function state() {
  const response = await fetch('api/state');
  if (!response.ok) throw new Error(`state: HTTP ${response.status}`);
  return response.json();
}

export async function binary(path) {
  const response = await fetch(`api/${path}`);
  if (!response.ok) throw new Error(`${path}: HTTP ${response.status}`);
  return response.arrayBuffer();
}
