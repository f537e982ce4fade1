// HairSheet Studio's page: wires the 3D view, the tools, the panel and the keys to the server.
import { HairView } from './hair-view.js';
import { ViewTool, CutTool, SelectTool, FitTool, HeadTool, PaintTool } from './tools.js';
import { command, state, binary } from './api.js';

const $ = id => document.getElementById(id);

class Studio {
  constructor() {
    this.view = new HairView($('view'));
    this.overlay = $('overlay');
    this.tools = {
      view: new ViewTool(this), cut: new CutTool(this), select: new SelectTool(this), fit: new FitTool(this), head: new HeadTool(this),
      paint: new PaintTool(this),
    };
    this.options = {
      selectShape: 'rectangle', rootsOnly: true, visibleOnly: true, brushRadius: 30,
      paintShape: 'brush', paintMode: 'add', hideHairWhilePainting: true,
    };
    this.head = { position: [0, 0, 0], yaw: 0, pitch: 0, roll: 0, shake: false };
    this.state = null;
    this.framesReceived = 0;
    this.framesDrawn = 0;
    this.received = [];          // arrival times of the last second's frames, for the rate shown
    this.ready = false;
    this.busy = 0;
    this.bindPanel();
    this.bindPointer();
    this.bindKeys();
    this.setTool('view');
  }

  async start() {
    await this.refreshState();
    this.pumpFrames();
    setInterval(() => this.refreshState().catch(e => this.say(e.message, true)), 250);
    const draw = () => { this.drawOverlay(); this.view.render(); this.framesDrawn++; requestAnimationFrame(draw); };
    requestAnimationFrame(draw);
  }

  /** Fetches frames one after another (one in flight); new topology whenever the strands' live counts may have changed. */
  async pumpFrames() {
    for (;;) {
      try {
        const buffer = await binary('frame');
        let header = this.view.setFrame(buffer);
        if (!this.view.topology || this.view.topology.revision !== header.revision || this.view.topology.particles !== header.particles) {
          this.view.setTopology(await binary('topology'));
          header = this.view.setFrame(buffer);
        }
        this.lastHeader = header;
        this.framesReceived++;
        const now = performance.now();
        this.received.push(now);
        while (this.received[0] < now - 1000) this.received.shift();
        this.ready = true;
      } catch (e) {
        this.say(`Lost the server: ${e.message}`, true);
        await new Promise(r => setTimeout(r, 1000));
      }
      await new Promise(r => requestAnimationFrame(r));
    }
  }

  async refreshState() {
    // A state asked for before a command was sent may answer after it: it must not undo the user's change on the page.
    const issued = this.commands;
    const s = await state();
    this.state = s;
    this.view.setColliders(s.colliders);
    const meshKey = s.hasMesh ? `${s.groom}/${s.particles}` : '';
    if (meshKey !== this.meshKey) {
      this.meshKey = meshKey;
      this.view.setHeadMesh(s.hasMesh ? await binary('mesh') : null);
    }
    // The painted scalp, fetched again whenever its revision moves.
    if (!s.scalp) { if (this.scalpRevision != null) this.scalpRevision = this.view.setScalpMask(null); }
    else if (s.scalp.revision !== this.scalpRevision) this.scalpRevision = this.view.setScalpMask(await binary('scalp'));
    if (!sameArray(s.selection, this.lastSelection)) { this.lastSelection = s.selection; this.view.setSelection(s.selection); }
    this.showState(s, issued === this.commands && this.busy === 0);
  }

  /** Runs a server command, shows its answer or its error, and refreshes the state. */
  async run(action) {
    this.commands = (this.commands ?? 0) + 1;
    this.busy++;
    try { this.say(await action()); } catch (e) { this.say(e.message, true); } finally { this.busy--; }
    await this.refreshState();
  }

  say(text, error = false) {
    const m = $('message');
    m.textContent = text;
    m.classList.toggle('error', error);
    clearTimeout(this.sayTimer);
    if (text) this.sayTimer = setTimeout(() => { m.textContent = ''; }, error ? 8000 : 4000);
  }

  setTool(name) {
    this.tool?.cancel();
    this.toolName = name;
    this.tool = this.tools[name];
    for (const b of document.querySelectorAll('[data-tool]')) b.classList.toggle('active', b.dataset.tool === name);
    $('stage').classList.toggle('drawing', this.tool.drawing);
    $('hint').textContent = {
      view: 'Drag to orbit, wheel to zoom, shift-drag to pan.',
      cut: 'Draw across the hair where it should end.',
      select: 'Drag to select strands (shift adds, alt removes). Right-drag orbits.',
      fit: 'Draw from the selected strands\u2019 roots the shape they should take.',
      head: 'Drag to move the head, shift-drag to turn it.',
      paint: 'Paint where hair grows on the head mesh (Alt erases); then Grow on scalp. Right-drag orbits.',
    }[name];
    // The shape radios show the shape of the tool in use (select and paint each keep their own).
    const shape = name === 'paint' ? this.options.paintShape : this.options.selectShape;
    for (const r of document.querySelectorAll('input[name=shape]')) r.checked = r.value === shape;
    this.view.setPainting(name === 'paint', this.options.hideHairWhilePainting);
    if (this.state) this.showState(this.state);
  }

  /** Undo and redo act on the scalp's paint strokes while the Paint scalp tool is in use, on the hair otherwise. */
  get undoTarget() { return this.toolName === 'paint' && this.state?.scalp ? 'scalp/' : ''; }

  sendHead() {
    // At most one head message in flight; the latest pose wins.
    if (this.headInFlight) { this.headPending = true; return; }
    this.headInFlight = true;
    command('head', this.head).catch(e => this.say(e.message, true)).finally(() => {
      this.headInFlight = false;
      if (this.headPending) { this.headPending = false; this.sendHead(); }
    });
  }

  bindPointer() {
    const overlay = this.overlay;
    const at = e => { const r = overlay.getBoundingClientRect(); return [e.clientX - r.left, e.clientY - r.top]; };
    overlay.addEventListener('pointerdown', e => {
      if (e.button !== 0 || !this.tool.drawing) return;   // other buttons reach the orbit controls
      e.stopPropagation();
      overlay.setPointerCapture(e.pointerId);
      this.tool.down(at(e), e);
    });
    overlay.addEventListener('pointermove', e => { if (this.tool.points) this.tool.move(at(e), e); });
    overlay.addEventListener('pointerup', e => { if (this.tool.points) this.tool.up(at(e), e); });
    overlay.addEventListener('pointercancel', () => this.tool.cancel());
    overlay.addEventListener('contextmenu', e => e.preventDefault());
  }

  drawOverlay() {
    const o = this.overlay, dpr = window.devicePixelRatio || 1;
    const w = Math.round(o.clientWidth * dpr), h = Math.round(o.clientHeight * dpr);
    if (o.width !== w || o.height !== h) { o.width = w; o.height = h; }
    const g = o.getContext('2d');
    // reset() rather than clearRect: Chromium with software WebGL was seen keeping parts of a stroke after clearRect.
    if (g.reset) g.reset(); else { g.setTransform(1, 0, 0, 1, 0, 0); g.clearRect(0, 0, o.width, o.height); }
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    this.tool.draw(g);
  }

  bindKeys() {
    window.addEventListener('keydown', e => {
      const k = e.key, ctrl = e.ctrlKey || e.metaKey;
      // Keys typed into a field or a list are theirs; a ticked checkbox or radio still lets Ctrl+Z and the like through.
      const toggle = e.target instanceof HTMLInputElement && (e.target.type === 'checkbox' || e.target.type === 'radio');
      if ((e.target instanceof HTMLInputElement && !(toggle && ctrl)) || e.target instanceof HTMLSelectElement) return;
      if (ctrl && (k === 'z' || k === 'Z')) { e.preventDefault(); this.run(() => command(this.undoTarget + (e.shiftKey ? 'redo' : 'undo'))); return; }
      if (ctrl && (k === 'y' || k === 'Y')) { e.preventDefault(); this.run(() => command(`${this.undoTarget}redo`)); return; }
      if (ctrl) return;
      const tools = { 1: 'view', 2: 'cut', 3: 'select', 4: 'fit', 5: 'head', 6: 'paint' };
      if (tools[k]) { this.setTool(tools[k]); return; }
      const views = { F1: 'front', F2: 'side', F3: 'back', F4: 'top' };
      if (views[k]) { e.preventDefault(); this.view.setView(views[k]); return; }
      const step = 0.01, turn = 5 * Math.PI / 180, h = this.head;
      const moves = {
        ArrowLeft: () => { h.position[0] -= step; }, ArrowRight: () => { h.position[0] += step; },
        ArrowUp: () => { h.position[1] += step; }, ArrowDown: () => { h.position[1] -= step; },
        a: () => { h.yaw += turn; }, d: () => { h.yaw -= turn; }, w: () => { h.pitch -= turn; }, s: () => { h.pitch += turn; },
        ' ': () => { h.shake = !h.shake; $('shake').checked = h.shake; },
      };
      if (moves[k]) { e.preventDefault(); moves[k](); this.sendHead(); return; }
      if (k === 'p') { $('pause').checked = !$('pause').checked; this.run(() => command(`pause?paused=${$('pause').checked}`)); }
      if (k === 'Escape') this.run(() => command('select/clear'));
    });
  }

  bindPanel() {
    for (const b of document.querySelectorAll('[data-tool]')) b.addEventListener('click', () => this.setTool(b.dataset.tool));
    for (const b of document.querySelectorAll('[data-view]')) b.addEventListener('click', () => this.view.setView(b.dataset.view));
    for (const r of document.querySelectorAll('input[name=shape]')) {
      r.addEventListener('change', () => { this.options[this.toolName === 'paint' ? 'paintShape' : 'selectShape'] = r.value; });
    }
    $('roots-only').addEventListener('change', e => { this.options.rootsOnly = e.target.checked; });
    $('visible-only').addEventListener('change', e => { this.options.visibleOnly = e.target.checked; });
    $('brush-radius').addEventListener('input', e => { this.options.brushRadius = +e.target.value; });
    $('clear-selection').addEventListener('click', () => this.run(() => command('select/clear')));
    $('undo').addEventListener('click', () => this.run(() => command(`${this.undoTarget}undo`)));
    $('redo').addEventListener('click', () => this.run(() => command(`${this.undoTarget}redo`)));
    for (const r of document.querySelectorAll('input[name=paint-mode]')) r.addEventListener('change', () => { this.options.paintMode = r.value; });
    $('hide-hair').addEventListener('change', e => {
      this.options.hideHairWhilePainting = e.target.checked;
      this.view.setPainting(this.toolName === 'paint', e.target.checked);
    });
    $('scalp-clear').addEventListener('click', () => this.run(() => command('scalp/fill', { to: 'none' })));
    $('scalp-all').addEventListener('click', () => this.run(() => command('scalp/fill', { to: 'all' })));
    $('scalp-colours').addEventListener('click', () => this.run(() => command('scalp/fill', { to: 'colours' })));
    $('scalp-grow').addEventListener('click', () => this.run(() => {
      this.say('Growing hair on the painted scalp\u2026');
      return command('scalp/grow');
    }));
    $('regrow').addEventListener('click', () => this.run(() => command('regrow')));
    $('reset').addEventListener('click', () => this.run(() => command('reset')));
    $('load-file').addEventListener('change', async e => {
      const file = e.target.files[0];
      e.target.value = '';
      if (file) await this.run(async () => command('load', await file.arrayBuffer()));
      this.syncHeadFromState();
    });
    $('shake').addEventListener('change', e => { this.head.shake = e.target.checked; this.sendHead(); });
    $('pause').addEventListener('change', e => this.run(() => command(`pause?paused=${e.target.checked}`)));
    $('head-home').addEventListener('click', () => { Object.assign(this.head, { position: [0, 0, 0], yaw: 0, pitch: 0, roll: 0 }); this.sendHead(); });

    // Settings: sag on a log scale (0.001 … 2), the rest linear; sent a moment after the slider stops.
    const sliders = {
      sag: { toValue: v => 10 ** (-3 + 3.3 * v / 100), toSlider: s => Math.round(100 * (Math.log10(Math.max(s, 1e-3)) + 3) / 3.3), fmt: v => v.toFixed(3) },
      bendDamping: {}, damping: {}, gravity: { fmt: v => `${v.toFixed(2)} g` }, substeps: {}, staticFriction: {}, kineticFriction: {},
      volumeStiffness: {}, volumeFriction: {}, volumeDensity: {},
    };
    this.sliders = sliders;
    for (const [name, s] of Object.entries(sliders)) {
      s.toValue ??= v => +v; s.toSlider ??= v => v; s.fmt ??= v => (Number.isInteger(v) ? `${v}` : v.toFixed(2));
      $(name).addEventListener('input', e => {
        const value = s.toValue(+e.target.value);
        $(`${name}-value`).textContent = s.fmt(value);
        clearTimeout(s.timer);
        s.editing = true;
        s.timer = setTimeout(() => { s.editing = false; this.run(() => command('settings', { [name]: value })); }, 150);
      });
    }
    $('path').addEventListener('change', e => this.run(() => command('settings', { path: e.target.value })));
    $('volume').addEventListener('change', e => this.run(() => command('settings', { volume: e.target.checked })));
    $('show').value = String(this.view.strandStride);
    $('show').addEventListener('change', e => this.view.setStrandStride(+e.target.value));
    $('density').addEventListener('input', e => { $('density-value').textContent = e.target.value; });
    $('groom').addEventListener('change', e => { this.groomChoice = e.target.value; });
    $('grow').addEventListener('click', async () => {
      await this.run(() => command('groom', { name: $('groom').value, strandsPerSheet: +$('density').value }));
      this.groomChoice = null;
      this.syncHeadFromState();
    });
  }

  syncHeadFromState() {
    const h = this.state?.head;
    if (h) Object.assign(this.head, { position: [...h.position], yaw: h.yaw, pitch: h.pitch, roll: h.roll, shake: h.shake });
    $('shake').checked = this.head.shake;
  }

  showState(s, current = true) {
    const groom = $('groom');
    if (groom.options.length !== s.grooms.length) {
      groom.replaceChildren(...s.grooms.map(g => new Option(`${g.name}: ${g.description}`, g.name)));
    }
    // The server's groom, unless the user has picked another one and not grown it yet.
    if (!this.groomChoice && s.grooms.some(g => g.name === s.groom)) groom.value = s.groom;
    for (const [name, slider] of Object.entries(this.sliders)) {
      if (slider.editing || document.activeElement === $(name)) continue;
      $(name).value = slider.toSlider(s.settings[name]);
      $(`${name}-value`).textContent = slider.fmt(s.settings[name]);
    }
    if (document.activeElement !== $('path')) $('path').value = s.settings.path;
    if (current) $('volume').checked = !!s.settings.volume;
    const paintUndo = this.undoTarget !== '';
    $('undo').disabled = (paintUndo ? s.scalp.undoCount : s.undoCount) === 0;
    $('redo').disabled = (paintUndo ? s.scalp.redoCount : s.redoCount) === 0;
    $('undo').title = paintUndo ? 'Undo the last scalp stroke (Ctrl+Z)' : 'Ctrl+Z';
    $('redo').title = paintUndo ? 'Redo a scalp stroke (Ctrl+Shift+Z or Ctrl+Y)' : 'Ctrl+Shift+Z or Ctrl+Y';
    const sc = s.scalp;
    $('scalp-info').textContent = sc
      ? `${sc.areaCm2.toFixed(0)} cm\u00b2 painted (${sc.painted.toLocaleString()} of ${sc.triangles.toLocaleString()} triangles): grows ${sc.growStrands.toLocaleString()} strands`
      : 'Grow the mesh head groom to paint its scalp.';
    $('scalp-grow').disabled = !sc || sc.growing;
    $('regrow').disabled = !s.canRegrow;
    $('pause').checked = s.paused;
    const m = s.metrics, rate = this.received.length;
    const rows = [
      ['strands', `${s.strands.toLocaleString()} (${s.cutStrands.toLocaleString()} cut)`],
      ['particles live / all', `${s.liveParticles.toLocaleString()} / ${s.particles.toLocaleString()}`],
      ['selected strands', s.selection.length.toLocaleString()],
      ['simulation step', `${s.stepMs.toFixed(2)} ms (worst ${s.stepMsWorst.toFixed(1)})`],
      ['simulation rate', `${s.simHz.toFixed(0)} Hz of 60`],
      ['frames shown', `${rate} /s`],
      ['length / rest length', `${(100 * m.lengthRatio).toFixed(3)} %`],
      ['largest stretch', `${(100 * m.maxEdgeStretch).toFixed(3)} %`],
      ['deepest penetration', `${m.maxPenetrationMm.toFixed(3)} mm (${m.particlesInside} inside)`],
      ['undo / redo', `${s.undoCount} / ${s.redoCount}`],
      ...(s.scalp ? [['scalp strokes undo / redo', `${s.scalp.undoCount} / ${s.scalp.redoCount}`]] : []),
      ['time', `${s.simTime.toFixed(1)} s${s.paused ? ' (paused)' : ''}`],
    ];
    $('figures').replaceChildren(...rows.map(([k, v]) => {
      const tr = document.createElement('tr');
      tr.append(Object.assign(document.createElement('td'), { textContent: k }), Object.assign(document.createElement('td'), { textContent: v }));
      return tr;
    }));
  }
}

function sameArray(a, b) { return a && b && a.length === b.length && a.every((x, i) => x === b[i]); }

const studio = new Studio();
window.studio = studio;   // for the browser tests and the console
studio.start().catch(e => studio.say(`Could not reach the studio server: ${e.message}`, true));
