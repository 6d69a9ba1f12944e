// Petra in Open MCT: one folder per telemetry packet, one telemetry point per
// field, from the dictionary the station generates from the packet
// definitions (GET /api/dictionary); the event list and the command history
// (ACK) and the link's sequence gaps as tables. History comes from the
// station's archive (GET /api/history, /api/gaps), realtime from its event
// stream (GET /api/events).
const NS = 'petra';
const SEVERITIES = ['DEBUG', 'INFO', 'WARNING', 'ERROR', 'FATAL'];
const utc = { key: 'utc', source: 'utc', name: 'Spacecraft time', format: 'utc', hints: { domain: 1 } };
const text = (key, name, extra = {}) => ({ key, name, format: 'string', hints: {}, ...extra });

const TABLES = {
  events: { name: 'Events', packet: 'EVENT', values: [utc,
    text('severity', 'Severity', { filters: [{ comparator: 'equals', possibleValues: SEVERITIES.map((s) => ({ label: s, value: s })) }] }),
    text('event', 'Event'), text('text', 'Text')],
    datum: (t, fields, names) => ({ utc: t, severity: names.severity, event: names.event, text: fields.text }) },
  commands: { name: 'Command history', packet: 'ACK', values: [utc, text('command', 'Command'), text('counter', 'Counter'),
    text('stage', 'Stage'), text('reason', 'Reason'), text('detail', 'Detail')],
    datum: (t, fields, names) => ({ utc: t, command: names.command, counter: fields.counter, stage: names.stage,
                                    reason: fields.reason ? names.reason : '', detail: names.detail || '' }) },
  // Not a packet: each packet with packets of its APID missing just before it.
  gaps: { name: 'Link gaps', values: [utc, text('packet', 'Packet'), text('seq', 'Sequence count'),
    text('missing', 'Missing before')],
    datum: (t, tlm) => ({ utc: t, packet: tlm.packet, seq: tlm.seq, missing: tlm.missing ?? tlm.missing_before }) },
};

// The value of "name" or "name[k]" in a packet's fields.
function fieldValue(fields, key) {
  const m = /^(.*)\[(\d+)\]$/.exec(key);
  return m ? fields[m[1]]?.[Number(m[2])] : fields[key];
}

export default function PetraPlugin() {
  return function install(openmct) {
    const dictionary = fetch('/api/dictionary').then((r) => r.json());
    const points = dictionary.then((d) => {
      const map = new Map();
      for (const p of d.packets) for (const pt of p.points) map.set(`${p.name}.${pt.key}`, { packet: p.name, ...pt });
      return map;
    });

    openmct.types.addType('petra.point', { name: 'Petra telemetry point', cssClass: 'icon-telemetry' });
    openmct.types.addType('petra.table', { name: 'Petra packet table', cssClass: 'icon-tabular-realtime' });
    openmct.objects.addRoot({ namespace: NS, key: 'root' });
    openmct.objects.addProvider(NS, {
      get: async (id) => {
        const d = await dictionary;
        if (id.key === 'root') return { identifier: id, name: 'Petra', type: 'folder', location: 'ROOT' };
        if (TABLES[id.key]) return { identifier: id, name: TABLES[id.key].name, type: 'petra.table',
          location: `${NS}:root`, telemetry: { values: TABLES[id.key].values } };
        const packet = d.packets.find((p) => p.name === id.key);
        if (packet) return { identifier: id, name: packet.name, type: 'folder', location: `${NS}:root` };
        const pt = (await points).get(id.key);
        if (!pt) return undefined;
        return { identifier: id, name: `${pt.packet} ${pt.key}`, type: 'petra.point', location: `${NS}:${pt.packet}`,
          telemetry: { values: [utc, { key: 'value', name: pt.key, unit: pt.unit, format: 'float',
            min: pt.min, max: pt.max, hints: { range: 1 } }] } };
      },
    });
    openmct.composition.addProvider({
      appliesTo: (o) => o.identifier.namespace === NS && o.type === 'folder',
      load: async (o) => {
        const d = await dictionary;
        if (o.identifier.key === 'root')
          return [...Object.keys(TABLES), ...d.packets.map((p) => p.name)].map((key) => ({ namespace: NS, key }));
        const packet = d.packets.find((p) => p.name === o.identifier.key);
        return packet.points.map((pt) => ({ namespace: NS, key: `${packet.name}.${pt.key}` }));
      },
    });

    // One stream of the station's messages for every subscription.
    const listeners = new Set();
    let source = null;
    function listen(fn) {
      if (!source) {
        source = new EventSource('/api/events');
        source.addEventListener('tlm', (e) => {
          const m = JSON.parse(e.data);
          for (const l of listeners) l(m);
        });
      }
      listeners.add(fn);
      return () => listeners.delete(fn);
    }

    openmct.telemetry.addProvider({
      supportsRequest: (o) => o.identifier.namespace === NS && o.telemetry !== undefined,
      supportsSubscribe: (o) => o.identifier.namespace === NS && o.telemetry !== undefined,
      request: async (o, options) => {
        const table = TABLES[o.identifier.key];
        const q = new URLSearchParams({ start: options.start, end: options.end });
        if (o.identifier.key === 'gaps') {
          const r = await fetch(`/api/gaps?${q}`);
          return r.ok ? (await r.json()).map((x) => table.datum(x.t, x)) : [];
        }
        if (table) {
          q.set('packet', table.packet);
          const wanted = options.filters?.severity?.equals;
          if (wanted?.length) q.set('min_severity', Math.min(...wanted.map((s) => SEVERITIES.indexOf(s))));
        } else {
          const [packet, ...field] = o.identifier.key.split('.');
          q.set('packet', packet);
          q.set('field', field.join('.'));
        }
        const r = await fetch(`/api/history?${q}`);
        if (!r.ok) return [];
        const rows = await r.json();
        if (!table) return rows.map((x) => ({ utc: x.t, value: x.v }));
        const wanted = options.filters?.severity?.equals;
        return rows.map((x) => table.datum(x.t, x.packet.fields, x.names))
          .filter((d) => !wanted?.length || wanted.includes(d.severity));
      },
      subscribe: (o, callback, options) => {
        const table = TABLES[o.identifier.key];
        const [packet, ...field] = o.identifier.key.split('.');
        const key = field.join('.');
        return listen((m) => {
          const t = m.tlm.time * 1000;
          if (o.identifier.key === 'gaps') {
            if (m.tlm.missing_before > 0) callback(table.datum(t, m.tlm));
          } else if (table) {
            if (m.tlm.packet !== table.packet) return;
            const d = table.datum(t, m.tlm.fields, m.names);
            const wanted = options?.filters?.severity?.equals;
            if (!wanted?.length || wanted.includes(d.severity)) callback(d);
          } else if (m.tlm.packet === packet) {
            const v = fieldValue(m.tlm.fields, key);
            if (typeof v === 'number') callback({ utc: t, value: v });
          }
        });
      },
    });
  };
}
