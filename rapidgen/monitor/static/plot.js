// Small canvas drawings for the monitor: a time series with its thresholds, and the site
// map with the traverse. Text drawn on a canvas is never markup.
"use strict";

const Plot = (() => {
  const WARN = "rgb(230, 145, 0)", CRIT = "rgb(210, 30, 30)", TRAVERSE = "rgb(40, 90, 200)";

  function fmt(v) {
    const a = Math.abs(v);
    return a !== 0 && (a < 0.01 || a >= 1e5) ? v.toExponential(2) : String(+v.toFixed(3));
  }

  // points: [[t, v], ...]; opts: {now, window, title, unit, warning, critical}
  function series(canvas, points, opts) {
    const ctx = canvas.getContext("2d"), w = canvas.width, h = canvas.height;
    const left = 52, right = 8, top = 18, bottom = 18;
    ctx.clearRect(0, 0, w, h);
    const t0 = opts.now - opts.window;
    const shown = points.filter(p => p[0] >= t0);
    let lo = Infinity, hi = -Infinity;
    for (const p of shown) { lo = Math.min(lo, p[1]); hi = Math.max(hi, p[1]); }
    for (const lvl of [opts.warning, opts.critical]) {
      if (!lvl) continue;
      for (const k of ["below", "above"]) if (lvl[k] !== null && lvl[k] !== undefined) { lo = Math.min(lo, lvl[k]); hi = Math.max(hi, lvl[k]); }
    }
    if (!isFinite(lo)) { lo = 0; hi = 1; }
    if (hi - lo < 1e-9) { lo -= 1; hi += 1; }
    const pad = (hi - lo) * 0.08; lo -= pad; hi += pad;
    const x = t => left + (t - t0) / opts.window * (w - left - right);
    const y = v => top + (hi - v) / (hi - lo) * (h - top - bottom);
    ctx.font = "11px system-ui, sans-serif";
    ctx.fillStyle = "#1d232b";
    ctx.fillText(opts.title + (opts.unit ? " [" + opts.unit + "]" : ""), left, 12);
    ctx.fillStyle = "#6b7380";
    ctx.fillText(fmt(hi), 2, top + 8);
    ctx.fillText(fmt(lo), 2, h - bottom);
    ctx.fillText("-" + Math.round(opts.window) + " s", left, h - 4);
    ctx.fillText("now", w - right - 22, h - 4);
    ctx.strokeStyle = "#d8dce2";
    ctx.strokeRect(left, top, w - left - right, h - top - bottom);
    for (const [lvl, colour] of [[opts.warning, WARN], [opts.critical, CRIT]]) {
      if (!lvl) continue;
      ctx.strokeStyle = colour; ctx.setLineDash([4, 3]);
      for (const k of ["below", "above"]) {
        if (lvl[k] === null || lvl[k] === undefined) continue;
        ctx.beginPath(); ctx.moveTo(left, y(lvl[k])); ctx.lineTo(w - right, y(lvl[k])); ctx.stroke();
      }
      ctx.setLineDash([]);
    }
    ctx.strokeStyle = TRAVERSE; ctx.lineWidth = 1.5; ctx.beginPath();
    shown.forEach((p, i) => i ? ctx.lineTo(x(p[0]), y(p[1])) : ctx.moveTo(x(p[0]), y(p[1])));
    ctx.stroke(); ctx.lineWidth = 1;
  }

  // traverse: [[x, y, t], ...] in the site frame (x north, y east); pos: {xyz, heading};
  // others: the other assets ({name, traverse, pos}), drawn in grey with their names
  function map(canvas, traverse, pos, others) {
    const ctx = canvas.getContext("2d"), w = canvas.width, h = canvas.height;
    ctx.clearRect(0, 0, w, h);
    const ok = p => p && isFinite(p.xyz[0]) && isFinite(p.xyz[1]);
    const pts = traverse.map(p => [p[0], p[1]]);
    if (ok(pos)) pts.push([pos.xyz[0], pos.xyz[1]]);
    for (const o of others || []) {
      for (const p of o.traverse) pts.push([p[0], p[1]]);
      if (ok(o.pos)) pts.push([o.pos.xyz[0], o.pos.xyz[1]]);
    }
    let minX = -5, maxX = 5, minY = -5, maxY = 5;
    for (const [a, b] of pts) { minX = Math.min(minX, a); maxX = Math.max(maxX, a); minY = Math.min(minY, b); maxY = Math.max(maxY, b); }
    const span = Math.max(maxX - minX, maxY - minY) * 1.15, cx = (minX + maxX) / 2, cy = (minY + maxY) / 2;
    const scale = Math.min(w, h) / span;
    // north up, east right: screen x from site y, screen y from site x
    const sx = e => w / 2 + (e - cy) * scale, sy = n => h / 2 - (n - cx) * scale;
    const step = Math.pow(10, Math.floor(Math.log10(span / 2)));
    ctx.strokeStyle = "#e4e1d6"; ctx.fillStyle = "#8a8577"; ctx.font = "10px system-ui, sans-serif";
    for (let e = Math.ceil((cy - span) / step) * step; e <= cy + span; e += step) {
      ctx.beginPath(); ctx.moveTo(sx(e), 0); ctx.lineTo(sx(e), h); ctx.stroke();
    }
    for (let n = Math.ceil((cx - span) / step) * step; n <= cx + span; n += step) {
      ctx.beginPath(); ctx.moveTo(0, sy(n)); ctx.lineTo(w, sy(n)); ctx.stroke();
    }
    ctx.fillText("grid " + step + " m, north up", 6, h - 6);
    ctx.fillStyle = "#444"; ctx.beginPath(); ctx.arc(sx(0), sy(0), 3, 0, 2 * Math.PI); ctx.fill();
    ctx.fillText("site origin", sx(0) + 5, sy(0) - 5);
    for (const o of others || []) {
      ctx.strokeStyle = "#a9a9b3"; ctx.lineWidth = 2; ctx.beginPath();
      o.traverse.forEach((p, i) => i ? ctx.lineTo(sx(p[1]), sy(p[0])) : ctx.moveTo(sx(p[1]), sy(p[0])));
      ctx.stroke(); ctx.lineWidth = 1;
      if (ok(o.pos)) {
        ctx.fillStyle = "#70707a"; ctx.beginPath(); ctx.arc(sx(o.pos.xyz[1]), sy(o.pos.xyz[0]), 5, 0, 2 * Math.PI); ctx.fill();
        ctx.fillText(String(o.name), sx(o.pos.xyz[1]) + 7, sy(o.pos.xyz[0]) + 4);
      }
    }
    if (traverse.length > 1) {
      ctx.strokeStyle = TRAVERSE; ctx.lineWidth = 3; ctx.beginPath();
      traverse.forEach((p, i) => i ? ctx.lineTo(sx(p[1]), sy(p[0])) : ctx.moveTo(sx(p[1]), sy(p[0])));
      ctx.stroke(); ctx.lineWidth = 1;
    }
    if (pos && isFinite(pos.xyz[0]) && isFinite(pos.xyz[1])) {
      const px = sx(pos.xyz[1]), py = sy(pos.xyz[0]), hd = isFinite(pos.heading) ? pos.heading : 0;
      ctx.save(); ctx.translate(px, py); ctx.rotate(hd);
      ctx.fillStyle = CRIT; ctx.beginPath(); ctx.moveTo(0, -11); ctx.lineTo(7, 8); ctx.lineTo(-7, 8); ctx.closePath(); ctx.fill();
      ctx.restore();
    }
  }

  return { series, map, TRAVERSE };
})();
