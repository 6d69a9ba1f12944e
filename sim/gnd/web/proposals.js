// The rock proposals (PROPOSE, issue 26): the request's controls, the ranked
// list of the last PROPOSALS packet, and its picture (PRODUCT "proposals",
// the left image with the proposals drawn on board). A click on the picture
// or on a row picks that proposal: the server sends SELECT_PROPOSAL for it
// (POST /api/proposals/pick); EVALUATE then runs the chain on its ROI.
import { drawImageProduct } from './products.js';

const fmt = (x, d = 1) => Number(x).toFixed(d);
const slot = (a, i, n) => a.slice(i * n, i * n + n);

export class ProposalsPanel {
  // els: {request, table, status, picture, caption}; send(command, args) -> counter | null;
  // palette: /api/palette; onPicked(result): after a pick was sent or refused.
  constructor(els, send, palette, onPicked) {
    this.els = els;
    this.send = send;
    this.palette = palette;
    this.onPicked = onPicked;
    this.list = null;   // fields of the last PROPOSALS
    this.planes = null; // fields of the last PROPOSAL_PLANES (every plane a proposal carries)
    this.names = null;  // its names (notes, verdicts, reaches, empty reason)
    this.picked = null; // rank
    els.picture.addEventListener('click', (e) => this.pickAt(e));
  }

  // The PROPOSE arguments from the form: the whole image unless a region is typed.
  request(form) {
    const n = (id) => Number(form[id].value);
    return { acquire: form.acquire.checked ? 1 : 0, x_px: n('x_px'), y_px: n('y_px'), w_px: n('w_px'),
             h_px: n('h_px'), count: n('count'), weight_grindable: n('weight_grindable'),
             weight_reach: n('weight_reach'), weight_certainty: n('weight_certainty'),
             weight_size: n('weight_size') };
  }

  onPacket(fields, names) {
    this.list = fields;
    this.names = names;
    this.picked = null;
    this.render();
  }

  // Every carried plane of the list shown (it follows PROPOSALS with the same id).
  onPlanes(fields) {
    this.planes = fields;
    this.render(false);
  }

  // The offered planes of rank i + 1 beyond the one shown, as "plane k: n (...)"
  // (ARM_GOTO_PROPOSAL_PLANE takes any of them).
  morePlanes(i) {
    const p = this.planes;
    if (!p || !this.list || p.proposal_id !== this.list.proposal_id) return '';
    const shown = slot(this.list.normal, i, 3).join();
    const perRank = p.offered.length / p.plane_count.length;  // plane slots per proposal
    const more = [];
    for (let j = 0; j < p.plane_count[i]; ++j) {
      const k = perRank * i + j;
      const n = slot(p.normal, k, 3);
      if (p.offered[k] === 1 && n.join() !== shown) more.push(`plane ${j + 1}: n (${n.map((a) => fmt(a, 3)).join(', ')})`);
    }
    return more.length ? `; also offered ${more.join('; ')}` : '';
  }

  // The picture of the list shown (same id); its pixels are image px / picture_step.
  onPicture(p) {
    if (!this.list || p.id !== this.list.proposal_id) return;
    if (drawImageProduct(this.els.picture, p))
      this.els.caption.textContent = `proposals ${p.id}: ${p.width} × ${p.height} px (1/${this.list.picture_step} of the image); click a rock to pick it`;
  }

  async pickAt(e) {
    if (!this.list || !this.list.picture_step) return;
    const c = this.els.picture;
    const r = c.getBoundingClientRect();
    const x = (e.clientX - r.left) * (c.width / r.width);
    const y = (e.clientY - r.top) * (c.height / r.height);
    const step = this.list.picture_step;
    await this.pick({ u: Math.floor(x * step), v: Math.floor(y * step) });
  }

  // body: {rank} or {u, v}; the server resolves it against the list it holds.
  async pick(body) {
    const r = await fetch('/api/proposals/pick', { method: 'POST', headers: { 'Content-Type': 'application/json' },
                                                   body: JSON.stringify(body) });
    const answer = await r.json().catch(() => ({ error: `HTTP ${r.status}` }));
    if (r.ok) {
      const rank = body.rank ?? this.rankAt(body.u, body.v);
      this.picked = rank;
      this.els.status.textContent = `Proposal ${rank} picked: ${answer.command} sent (counter ${answer.counter}); EVALUATE runs the chain on it.`;
      this.render(false);
    } else {
      this.els.status.textContent = `No pick: ${answer.error}`;
    }
    this.onPicked(r.ok ? answer : null);
  }

  // As the server's proposal_at: the best-ranked ROI holding (u, v).
  rankAt(u, v) {
    for (let i = 0; i < this.list.count; ++i) {
      const [x, y, w, h] = slot(this.list.roi_px, i, 4);
      if (u >= x && u < x + w && v >= y && v < y + h) return i + 1;
    }
    return null;
  }

  render(status = true) {
    const l = this.list;
    if (!l) return;
    if (status) {
      const why = l.status === 2 ? `failed (reason ${l.reason})` : l.status === 1 ? `nothing offered: ${this.names.empty_reason}` : 'best first';
      this.els.status.textContent = `Proposals ${l.proposal_id} on pair ${l.frame}: ${l.count} of ${l.candidates} rocks detected, ${l.total_ms} ms; ${why}.`;
    }
    const rows = [];
    for (let i = 0; i < l.count; ++i) rows.push(this.row(i));
    this.els.table.tBodies[0].replaceChildren(...rows);
  }

  row(i) {
    const l = this.list;
    const tr = document.createElement('tr');
    tr.dataset.rank = i + 1;
    if (this.picked === i + 1) tr.className = 'picked';
    const [x, y, w, h] = slot(l.roi_px, i, 4);
    const [u, v] = slot(l.click_px, i, 2);
    const offered = l.plane_offered[i] === 1;
    const plane = l.plane_count[i] === 0 ? 'none'
      : `${offered ? 'offered' : 'not offered'}: n (${slot(l.normal, i, 3).map((a) => fmt(a, 3)).join(', ')}), `
        + `${this.names.verdicts[i]}, reach ${this.names.reaches[i]}, σ ${fmt(l.normal_sigma_deg[i], 2)}° ${fmt(l.offset_sigma_mm[i], 2)} mm`
        + this.morePlanes(i);
    const cells = [l.rank[i], `${x}, ${y}, ${w} × ${h}`, `${u}, ${v}`, `${fmt(l.height_mm[i])} / ${fmt(l.size_mm[i])}`,
      l.planes_c[i], this.names.notes[i],
      `${fmt(l.score_total[i], 3)} (${[l.score_grindable[i], l.score_reach[i], l.score_certainty[i], l.score_size[i]].map((a) => fmt(a, 2)).join(' ')})`,
      plane];
    cells.forEach((text, k) => {
      const td = document.createElement('td');
      if (k === 0) {
        const s = document.createElement('span');
        s.className = 'swatch';
        s.style.background = offered ? this.palette.planes[Math.min(i, this.palette.planes.length - 1)] : this.palette.rejected;
        td.append(s);
      }
      td.append(String(text));
      tr.append(td);
    });
    tr.addEventListener('click', () => this.pick({ rank: i + 1 }));
    return tr;
  }
}
