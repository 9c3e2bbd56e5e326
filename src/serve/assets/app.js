// Placeholder until the page lands: analyse the start scene once.
(async () => {
  const { scene } = await (await fetch('api/scene')).json();
  const r = await (await fetch('api/analyze', { method: 'POST', body: JSON.stringify({ scene }) })).json();
  document.getElementById('drawing').innerHTML = r.svg || '';
  document.getElementById('lambda').textContent = r.error || `lambda = ${r.lambda_lower}`;
})();
