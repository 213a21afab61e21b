// vd workbench: renders the state the server pushes (Server-Sent Events) and sends edits.
'use strict';

let state = null;
let active = 'overview';
const marked = new Set();

function el(tag, attrs, ...children) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k === 'class') node.className = v;
    else if (k.startsWith('on')) node.addEventListener(k.slice(2), v);
    else if (v !== undefined && v !== null && v !== false) node.setAttribute(k, v === true ? '' : v);
  }
  for (const c of children.flat()) {
    if (c !== null && c !== undefined) node.append(c instanceof Node ? c : String(c));
  }
  return node;
}

function say(text, ok) {
  const box = document.getElementById('message');
  box.textContent = text;
  box.className = 'message ' + (ok ? 'ok' : 'error');
}

async function post(path, body) {
  let answer;
  try {
    const response = await fetch(path, {method: 'POST', headers: {'Content-Type': 'application/json'},
      body: JSON.stringify(body)});
    answer = await response.json();
  } catch (err) {
    say('the workbench server does not answer: ' + err, false);
    return null;
  }
  if (!answer.ok) { say(answer.error, false); return null; }
  say(answer.message, true);
  if (answer.state) render(answer.state);
  return answer;
}

function edit(body) { return post('/api/edit', body); }

function statusOf(config, group) {
  return state.status.status.find(s => s.configuration === config && s.group === group);
}

function option(value, label, selected) {
  return el('option', {value, selected: selected ? true : null}, label);
}

// -- overview (thesis Fig. 2.3.1) --------------------------------------------------------
function overviewTab() {
  const names = state.status.configurations;
  const head = el('tr', {}, el('th', {class: 'group'}, 'input group'),
    names.map(n => el('th', {}, el('label', {},
      el('input', {type: 'checkbox', id: `mark-${n}`, checked: marked.has(n) ? true : null,
        onchange: e => { e.target.checked ? marked.add(n) : marked.delete(n); }}), ' ', n))),
    el('th', {}, 'all configurations'));
  const rows = state.status.groups.map(group => {
    let consistency = 'SAME';
    const cells = names.map(n => {
      const s = statusOf(n, group);
      consistency = s.consistency;
      if (!s.variant) return el('td', {id: `cell-${n}-${group}`, class: 'notused', 'data-state': 'NOT_USED'}, '-');
      const title = s.modified_keys.map(m => `${m.key}: ${m.data_value} -> ${m.master_value} ${m.unit}`).join('\n');
      const label = state.edits
        ? el('select', {id: `variant-${n}-${group}`, onchange: e => edit({op: 'variant', configuration: n, group, value: e.target.value})},
          (state.available[group] || [s.variant]).map(v => option(v, v, v === s.variant)))
        : el('b', {}, s.variant);
      return el('td', {id: `cell-${n}-${group}`, class: s.state, 'data-state': s.state, title}, label, ' ', s.state);
    });
    return el('tr', {}, el('td', {class: 'group'}, el('a', {href: '#', onclick: e => { e.preventDefault(); show(group); }}, group)),
      cells, el('td', {class: consistency, id: `consistency-${group}`}, consistency));
  });
  const flex = state.status.flexible;
  const flexRow = el('tr', {}, el('td', {class: 'group'}, 'flexible components'),
    flex.map(f => el('td', {id: `flex-${f.configuration}`, class: f.flexible ? 'flex-on' : 'dim'},
      f.flexible ? 'on' + (f.components.length ? ` (${f.components.join(', ')})` : '') : 'off')),
    el('td', {class: flex.length ? flex[0].consistency : ''}, flex.length ? flex[0].consistency : ''));
  const ovRow = el('tr', {}, el('td', {class: 'group'}, 'overrides'),
    state.configurations.map(c => el('td', {id: `overrides-${c.name}`, style: 'text-align:left'},
      c.overrides.length ? c.overrides.map(o => el('div', {class: 'MODIFIED'}, `${o.key} = ${o.value}`,
        o.unit ? el('span', {class: 'dim'}, ` [${o.unit}]`) : null,
        state.edits ? el('button', {title: 'clear this override', 'data-clear': `${c.name}|${o.key}`,
          onclick: () => edit({op: 'override', configuration: c.name, key: o.key, value: ''})}, '✕') : null))
        : el('span', {class: 'dim'}, 'none'))),
    el('td', {}, ''));
  const descRow = el('tr', {}, el('td', {class: 'group'}, 'description'),
    state.configurations.map(c => el('td', {class: 'dim', style: 'max-width:18em'}, c.description)), el('td', {}, ''));
  const table = el('table', {id: 'overview'}, head, rows, flexRow, ovRow, descRow);
  return el('div', {}, table, editPanel(), runPanel());
}

function configSelect(id, withNone) {
  return el('select', {id}, withNone ? option('', '(new, empty)') : null,
    state.configurations.map(c => option(c.name, c.name)));
}

function keyList() {
  const keys = [];
  for (const [group, g] of Object.entries(state.groups)) {
    for (const row of g.rows) {
      if (row.type === 'scalar' || row.type === 'text') keys.push(`${group}.${row.key}`);
      if (row.type === 'point') for (const c of 'xyz') keys.push(`${group}.${row.key}.${c}`);
    }
  }
  return el('datalist', {id: 'override-keys'}, keys.map(k => option(k, k)));
}

function unitOf(dotted) {
  const [group, ...rest] = dotted.split('.');
  const g = state.groups[group];
  if (!g) return '';
  let key = rest.join('.');
  let row = g.rows.find(r => r.key === key);
  if (!row && /\.[xyz]$/.test(key)) row = g.rows.find(r => r.key === key.slice(0, -2));
  if (!row) return '';
  const cell = Object.values(row.cells)[0];
  return cell ? cell.unit : '';
}

function editPanel() {
  if (!state.edits) {
    return el('p', {class: 'dim', id: 'edits-off'}, 'Edits are off (start with vd gui --edits to change the master file).');
  }
  const unit = el('span', {id: 'ov-unit', class: 'dim'});
  const key = el('input', {id: 'ov-key', class: 'key', list: 'override-keys', placeholder: 'front_alignment.camber',
    oninput: e => { const u = unitOf(e.target.value); unit.textContent = u ? `unit of the data: ${u}` : ''; }});
  const value = el('input', {id: 'ov-value', class: 'value', placeholder: '-1.2 deg'});
  const ov = el('fieldset', {}, el('legend', {}, 'Override a value'), configSelect('ov-config'), ' ', key, keyList(), ' = ', value, ' ',
    el('button', {id: 'ov-set', onclick: () => edit({op: 'override', configuration: val('ov-config'), key: val('ov-key'), value: val('ov-value')})}, 'Set'), ' ',
    el('button', {id: 'ov-clear', onclick: () => edit({op: 'override', configuration: val('ov-config'), key: val('ov-key'), value: ''})}, 'Clear'),
    el('br'), unit);
  const fx = el('fieldset', {}, el('legend', {}, 'Flexible components'), configSelect('fx-config'), ' ',
    el('input', {id: 'fx-value', class: 'key', placeholder: 'on | off | lca, strut, upright'}), ' ',
    el('button', {id: 'fx-set', onclick: () => edit({op: 'flexible', configuration: val('fx-config'), value: val('fx-value')})}, 'Switch'));
  const add = el('fieldset', {}, el('legend', {}, 'Add or copy a configuration'),
    el('input', {id: 'add-name', placeholder: 'new_name'}), ' from ', configSelect('add-source', true), ' ',
    el('input', {id: 'add-description', class: 'key', placeholder: 'description'}), ' ',
    el('button', {id: 'add', onclick: () => edit({op: 'add', configuration: val('add-name'), source: val('add-source'), value: val('add-description')})}, 'Add'));
  return el('div', {id: 'edits'}, ov, fx, add);
}

function runPanel() {
  const rows = Object.entries(state.runs || {}).map(([name, r]) => el('tr', {id: `run-${name}`},
    el('td', {}, name), el('td', {}, r.status),
    el('td', {}, r.error ? el('span', {class: 'errors'}, r.error) :
      r.metrics.map(m => el('div', {}, `${m.event} ${m.model}: ${m.label} ${m.text}`)))));
  return el('div', {}, el('h3', {}, 'Results of the marked configurations'),
    state.can_run ? el('button', {id: 'run-marked', disabled: state.running ? true : null,
      onclick: () => post('/api/run', {configurations: [...marked]})}, state.running ? 'running…' : 'Update marked')
      : el('p', {class: 'dim'}, 'This workbench runs no events.'),
    rows.length ? el('table', {class: 'runs'}, el('tr', {}, el('th', {}, 'configuration'), el('th', {}, 'status'), el('th', {}, 'headline metrics')), rows) : null);
}

function val(id) { return document.getElementById(id).value; }

// -- one tab per input group (thesis Fig. 2.3.3) -----------------------------------------
function groupTab(group) {
  const g = state.groups[group];
  const names = state.status.configurations;
  const files = el('p', {class: 'dim'}, `kind ${g.kind}; files: `,
    Object.entries(g.files).map(([n, f]) => `${n}: ${f}`).join(', '));
  const head = el('tr', {}, el('th', {class: 'group'}, 'key'), names.map(n => el('th', {}, n)), el('th', {}, 'unit'),
    el('th', {}, 'all configurations'));
  const rows = g.rows.map(row => {
    const cells = names.map(n => {
      const c = row.cells[n];
      if (!c) return el('td', {class: 'notused'}, '-');
      return el('td', {id: `value-${group}-${n}-${row.key}`, class: c.modified ? 'modified' : '',
        title: (c.modified ? `data file: ${c.data_value}\n` : '') + c.source}, c.text);
    });
    const unit = Object.values(row.cells)[0];
    return el('tr', {class: row.consistency === 'DIFFERS' ? 'differs' : ''}, el('td', {class: 'key'}, row.key), cells,
      el('td', {}, unit ? unit.unit : ''), el('td', {class: row.consistency}, row.consistency));
  });
  const parts = [files, el('table', {id: `group-${group}`}, head, rows)];
  if (state.hardpoints[group]) parts.push(geometry(state.hardpoints[group]));
  return el('div', {}, parts);
}

const COLOURS = ['#1f5fbf', '#c0392b', '#27ae60', '#8e44ad', '#d68910', '#117a65'];

function geometry(byConfig) {
  // three orthographic views of the hard points (mm, vehicle frame: x forward, y left, z up)
  const views = [['side view (x, z)', 0, 2, -1], ['front view (y, z)', 1, 2, 1], ['top view (x, y)', 0, 1, -1]];
  const all = Object.values(byConfig).flatMap(points => Object.values(points));
  const svgNs = 'http://www.w3.org/2000/svg';
  const out = el('div', {id: 'geometry'}, el('h3', {}, 'Hard points'));
  const legend = el('p', {}, Object.keys(byConfig).map((n, i) => el('span', {style: `color:${COLOURS[i % COLOURS.length]};margin-right:1em`}, '● ' + n)));
  out.append(legend);
  for (const [title, a, b, sign] of views) {
    const xs = all.map(p => sign * p[a]), ys = all.map(p => p[b]);
    const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
    const span = Math.max(x1 - x0, y1 - y0, 1), size = 300, pad = 30;
    const sx = x => pad + (x - x0) / span * (size - 2 * pad), sy = y => size - pad - (y - y0) / span * (size - 2 * pad);
    const svg = document.createElementNS(svgNs, 'svg');
    svg.setAttribute('width', size); svg.setAttribute('height', size);
    const label = document.createElementNS(svgNs, 'text');
    label.setAttribute('x', 5); label.setAttribute('y', 14); label.setAttribute('font-size', 12);
    label.textContent = title;
    svg.append(label);
    Object.entries(byConfig).forEach(([n, points], i) => {
      for (const [name, p] of Object.entries(points)) {
        const dot = document.createElementNS(svgNs, 'circle');
        dot.setAttribute('cx', sx(sign * p[a])); dot.setAttribute('cy', sy(p[b])); dot.setAttribute('r', 3.5 - i * 0.6);
        dot.setAttribute('fill', COLOURS[i % COLOURS.length]);
        const tip = document.createElementNS(svgNs, 'title');
        tip.textContent = `${n} ${name} [${p.map(c => c.toFixed(1)).join(', ')}] mm`;
        dot.append(tip);
        svg.append(dot);
        if (i === 0) {
          const t = document.createElementNS(svgNs, 'text');
          t.setAttribute('x', sx(sign * p[a]) + 4); t.setAttribute('y', sy(p[b]) - 3); t.setAttribute('font-size', 8);
          t.textContent = name;
          svg.append(t);
        }
      }
    });
    out.append(svg);
  }
  const names = Object.keys(byConfig);
  const points = Object.keys(byConfig[names[0]]);
  out.append(el('table', {id: 'hardpoint-table'}, el('tr', {}, el('th', {}, `point [mm] (red: differs from ${names[0]})`), names.map(n => el('th', {}, n))),
    points.map(p => el('tr', {}, el('td', {class: 'key'}, p), names.map(n => {
      const q = byConfig[n][p], r = byConfig[names[0]][p];
      const differs = q && r && q.some((c, k) => Math.abs(c - r[k]) > 1e-9);
      return el('td', {class: differs ? 'modified' : ''}, q ? q.map(c => c.toFixed(1)).join(', ') : '-');
    })))));
  return out;
}

// -- tabs and rendering ------------------------------------------------------------------
function show(name) { active = name; render(state); }

function render(next) {
  if (!next || (state && next.version < state.version)) return;
  const keep = {};
  for (const input of document.querySelectorAll('#edits input, #edits select')) keep[input.id] = input.value;
  const focused = document.activeElement ? document.activeElement.id : '';
  state = next;
  document.getElementById('title').textContent = `vd workbench: ${state.name}`;
  document.getElementById('subtitle').textContent = `${state.master}  ·  ${state.description}`;
  document.body.dataset.version = state.version;
  document.getElementById('errors').textContent = state.errors.length
    ? 'The files on disk do not load; showing the last good data:\n' + state.errors.join('\n') : '';
  const tabs = document.getElementById('tabs');
  tabs.replaceChildren(...['overview', ...state.status.groups].map(name => el('button', {
    id: `tab-${name}`, class: name === active ? 'active' : '', onclick: () => show(name)}, name)));
  if (active !== 'overview' && !state.groups[active]) active = 'overview';
  document.getElementById('content').replaceChildren(active === 'overview' ? overviewTab() : groupTab(active));
  for (const [id, v] of Object.entries(keep)) { const input = document.getElementById(id); if (input) input.value = v; }
  if (focused && document.getElementById(focused)) document.getElementById(focused).focus();
}

function connect() {
  const events = new EventSource('/api/events');
  const line = document.getElementById('connection');
  events.addEventListener('state', e => { line.textContent = 'live: follows the files on disk'; render(JSON.parse(e.data)); });
  events.onerror = () => { line.textContent = 'connection lost; retrying…'; };
}

connect();
