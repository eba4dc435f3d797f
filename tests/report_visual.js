(function () {
  const inside = (p, b, m) => p.x > b.left + m && p.x < b.right - m && p.y > b.top + m && p.y < b.bottom - m;
  const out = [];
  document.querySelectorAll('svg').forEach((svg, k) => {
    const section = svg.closest('section');
    const cap = svg.querySelector('text');
    const name = (section ? section.id : 'svg' + k) + ' / ' + (cap ? cap.textContent : '');
    const kids = Array.from(svg.children);
    const bg = kids.findIndex(e => e.tagName === 'rect' && e.getAttribute('opacity') === '0.85');
    const mesh = kids.filter(e => e.tagName === 'line').map(e => e.getBoundingClientRect());
    if (mesh.length === 0) return;
    const area = {
      left: Math.min(...mesh.map(r => r.left)), right: Math.max(...mesh.map(r => r.right)),
      top: Math.min(...mesh.map(r => r.top)), bottom: Math.max(...mesh.map(r => r.bottom)),
    };
    const r = { name, legend: null, covered: 0, overflow: [], styles: [], overlaps: [] };
    if (bg >= 0) {
      const box = kids[bg].getBoundingClientRect();
      r.legend = [box.left, box.top, box.width, box.height];
      // Data drawn before the legend: lines sampled every 2 px, markers.
      for (const e of kids.slice(0, bg)) {
        if (e.tagName === 'polyline') {
          const pts = Array.from(e.points);
          if (pts.length < 2) continue;
          const m = e.getScreenCTM();
          const len = e.getTotalLength();
          for (let s = 0; s <= len; s += 2) {
            const q = e.getPointAtLength(s).matrixTransform(m);
            if (inside(q, area, 0.5) && inside(q, box, 1)) r.covered++;
          }
        } else if (e.tagName === 'circle') {
          const b = e.getBoundingClientRect();
          const c = { x: b.left + b.width / 2, y: b.top + b.height / 2 };
          if (inside(c, box, 1)) r.covered++;
        }
      }
      // The legend's own entries stay inside its box, the box inside the
      // figure, and no two entries look alike.
      const fig = svg.getBoundingClientRect();
      if (box.right > fig.right + 0.5 || box.bottom > fig.bottom + 0.5) r.overflow.push('legend box outside the figure');
      const rows = new Map();
      for (const e of kids.slice(bg + 2)) {
        const b = e.getBoundingClientRect();
        if (b.right > box.right + 0.5 || b.left < box.left - 0.5 || b.bottom > box.bottom + 0.5 || b.top < box.top - 0.5)
          r.overflow.push(e.tagName + ':' + (e.textContent || ''));
        if (e.tagName === 'text') continue;
        const row = Math.round((b.top + b.bottom) / 2);
        const paint = e.tagName === 'polyline' || e.tagName === 'line' ? e.getAttribute('stroke') : e.getAttribute('fill');
        const look = e.tagName + ' ' + paint + ' ' + Math.round(b.width) + 'x' + Math.round(b.height);
        if (!rows.has(row)) rows.set(row, []);
        rows.get(row).push(look);
      }
      r.styles = Array.from(rows.values()).map(v => v.sort().join(' + '));
    }
    // No two texts overlap.
    const texts = kids.filter(e => e.tagName === 'text').map(e => [e.textContent, e.getBoundingClientRect()]);
    for (let i = 0; i < texts.length; i++) for (let j = i + 1; j < texts.length; j++) {
      const a = texts[i][1], b = texts[j][1];
      if (a.left < b.right - 1 && b.left < a.right - 1 && a.top < b.bottom - 1 && b.top < a.bottom - 1)
        r.overlaps.push(texts[i][0] + ' | ' + texts[j][0]);
    }
    out.push(r);
  });
  const pre = document.createElement('pre');
  pre.id = 'visual-check';
  pre.textContent = JSON.stringify(out);
  document.body.appendChild(pre);
})();
