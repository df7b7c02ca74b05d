// A Foxglove WebSocket client made of the ecosystem's own packages (@foxglove/ws-protocol,
// ws, @foxglove/rosmsg, @foxglove/rosmsg2-serialization), driven by JSON lines on stdin;
// everything it sees goes to stdout as JSON lines. tests/bundled/test_foxglove_bridge.py and
// benchmarks/bench_foxglove.py drive it.
//
// usage: node foxglove_client.js ws://127.0.0.1:PORT [subprotocol,...]
'use strict';

const readline = require('readline');
const { FoxgloveClient } = require('@foxglove/ws-protocol');
const WebSocket = require('ws');
const { parse } = require('@foxglove/rosmsg');
const { MessageReader, MessageWriter } = require('@foxglove/rosmsg2-serialization');

const url = process.argv[2];
const protocols = (process.argv[3] || 'foxglove.sdk.v1').split(',');

function emit(obj) {
  process.stdout.write(
    JSON.stringify(obj, (_k, v) => (typeof v === 'bigint' ? Number(v) : v)) + '\n',
  );
}

// large arrays (image data) are summarised: length, a sum and the first bytes
function summarise(value) {
  if (ArrayBuffer.isView(value)) {
    let sum = 0;
    for (let i = 0; i < value.length; i++) sum = (sum + value[i]) % 1000000007;
    return { length: value.length, sum, head: Array.from(value.slice(0, 8)) };
  }
  if (Array.isArray(value)) return value.map(summarise);
  if (value && typeof value === 'object') {
    const out = {};
    for (const [k, v] of Object.entries(value)) out[k] = summarise(v);
    return out;
  }
  return value;
}

const ws = new WebSocket(url, protocols);
ws.on('unexpected-response', (_req, res) => {
  emit({ event: 'rejected', status: res.statusCode });
  process.exit(0);
});
ws.on('error', (e) => emit({ event: 'error', message: String(e.message || e) }));
const client = new FoxgloveClient({ ws });

const channels = new Map(); // id -> channel
const byTopic = new Map(); // topic -> channel
const readers = new Map(); // channel id -> MessageReader
const subscriptions = new Map(); // subscription id -> {topic, count, decode, stats}
const services = new Map(); // name -> service
const calls = new Map(); // call id -> service
let nextCall = 1;

function reader(channel) {
  let r = readers.get(channel.id);
  if (!r) {
    r = new MessageReader(parse(channel.schema, { ros2: true }));
    readers.set(channel.id, r);
  }
  return r;
}

client.on('open', () => emit({ event: 'open', protocol: ws.protocol }));
client.on('close', (e) => {
  emit({ event: 'close', code: e.code, reason: String(e.reason || '') });
  process.exit(0);
});
client.on('serverInfo', (info) => emit({ event: 'serverInfo', info }));
client.on('status', (s) => emit({ event: 'status', level: s.level, message: s.message }));
client.on('advertise', (list) => {
  const out = [];
  for (const ch of list) {
    channels.set(ch.id, ch);
    byTopic.set(ch.topic, ch);
    let parsed = false;
    let error = null;
    try {
      parse(ch.schema, { ros2: true });
      parsed = ch.schemaEncoding === 'ros2msg' && ch.encoding === 'cdr';
    } catch (e) {
      error = String(e.message || e);
    }
    out.push({ id: ch.id, topic: ch.topic, schemaName: ch.schemaName, parsed, error });
  }
  emit({ event: 'advertise', channels: out });
});
client.on('unadvertise', (ids) => {
  const topics = [];
  for (const id of ids) {
    const ch = channels.get(id);
    if (ch) {
      topics.push(ch.topic);
      channels.delete(id);
      if (byTopic.get(ch.topic) === ch) byTopic.delete(ch.topic);
    }
  }
  emit({ event: 'unadvertise', topics });
});
client.on('advertiseServices', (list) => {
  for (const s of list) services.set(s.name, s);
  emit({ event: 'advertiseServices', services: list.map((s) => ({ name: s.name, type: s.type })) });
});
client.on('message', (m) => {
  const sub = subscriptions.get(m.subscriptionId);
  if (!sub) return;
  const now = performance.now();
  if (sub.received === 0) sub.first = now;
  sub.last = now;
  sub.received += 1;
  sub.bytes += m.data.byteLength;
  if (sub.decode > 0) {
    sub.decode -= 1;
    const bytes = new Uint8Array(m.data.buffer, m.data.byteOffset, m.data.byteLength);
    const value = sub.reader.readMessage(bytes);
    emit({ event: 'message', topic: sub.topic, value: summarise(value) });
  }
});
client.on('parameterValues', (p) => emit({ event: 'parameterValues', id: p.id, parameters: p.parameters }));
client.on('connectionGraphUpdate', (g) => emit({ event: 'connectionGraph', graph: g }));
client.on('time', (t) => emit({ event: 'time', timestamp: Number(t.timestamp) }));
client.on('serviceCallResponse', (r) => {
  const service = calls.get(r.callId);
  calls.delete(r.callId);
  const schema = service.response ? service.response.schema : service.responseSchema;
  const bytes = new Uint8Array(r.data.buffer, r.data.byteOffset, r.data.byteLength);
  const value = new MessageReader(parse(schema, { ros2: true })).readMessage(bytes);
  emit({ event: 'serviceResponse', service: service.name, value: summarise(value) });
});
client.on('fetchAssetResponse', (r) => {
  if (r.status === 0) {
    const bytes = new Uint8Array(r.data.buffer, r.data.byteOffset, r.data.byteLength);
    const sha256 = require('crypto').createHash('sha256').update(bytes).digest('hex');
    emit({ event: 'asset', id: r.requestId, status: r.status, length: bytes.length, sha256 });
  } else {
    emit({ event: 'asset', id: r.requestId, status: r.status, error: r.error });
  }
});
client.on('serviceCallFailure', (f) => emit({ event: 'serviceFailure', message: f.message }));

const published = new Map(); // topic -> {id, writer}

function handle(cmd) {
  switch (cmd.cmd) {
    case 'subscribe': {
      const ch = byTopic.get(cmd.topic);
      if (!ch) return emit({ event: 'fail', message: `no channel ${cmd.topic}` });
      const id = client.subscribe(ch.id);
      subscriptions.set(id, {
        topic: cmd.topic, decode: cmd.decode ?? 1, received: 0, bytes: 0, reader: reader(ch),
      });
      return emit({ event: 'subscribed', topic: cmd.topic, id });
    }
    case 'unsubscribe': {
      for (const [id, sub] of subscriptions) {
        if (sub.topic === cmd.topic) {
          client.unsubscribe(id);
          subscriptions.delete(id);
        }
      }
      return emit({ event: 'unsubscribed', topic: cmd.topic });
    }
    case 'counts': {
      const counts = {};
      for (const sub of subscriptions.values()) {
        // arrival times in ms of this process' clock, for rates
        counts[sub.topic] = { received: sub.received, bytes: sub.bytes, first: sub.first, last: sub.last };
      }
      return emit({ event: 'counts', counts });
    }
    case 'publish': {
      let pub = published.get(cmd.topic);
      if (!pub) {
        const schemaName = cmd.schemaName;
        const encoding = cmd.encoding || 'cdr';
        const id = client.advertise({ topic: cmd.topic, encoding, schemaName });
        const definition = cmd.schema ? parse(cmd.schema, { ros2: true }) : null;
        pub = { id, encoding, writer: definition ? new MessageWriter(definition) : null };
        published.set(cmd.topic, pub);
      }
      const data = pub.encoding === 'json'
        ? new TextEncoder().encode(JSON.stringify(cmd.value))
        : pub.writer ? pub.writer.writeMessage(cmd.value) : Uint8Array.from(cmd.bytes || []);
      client.sendMessage(pub.id, data);
      return emit({ event: 'published', topic: cmd.topic });
    }
    case 'call': {
      const service = services.get(cmd.service);
      if (!service) return emit({ event: 'fail', message: `no service ${cmd.service}` });
      const schema = service.request ? service.request.schema : service.requestSchema;
      const data = new MessageWriter(parse(schema, { ros2: true })).writeMessage(cmd.request);
      const callId = nextCall++;
      calls.set(callId, service);
      return client.sendServiceCallRequest({ serviceId: service.id, callId, encoding: 'cdr', data });
    }
    case 'getParameters':
      return client.getParameters(cmd.names, cmd.id);
    case 'setParameters':
      return client.setParameters(cmd.parameters, cmd.id);
    case 'subscribeParameters':
      return client.subscribeParameterUpdates(cmd.names);
    case 'fetchAsset':
      return client.fetchAsset(cmd.uri, cmd.id);
    case 'subscribeGraph':
      return client.subscribeConnectionGraph();
    case 'raw':
      // bytes no well-behaved client sends, straight onto the socket
      return ws.send(cmd.binary ? Buffer.from(cmd.data, 'base64') : cmd.data);
    case 'subscribeIds': {
      // subscribe to channel ids that may not exist, through the client's own framing
      for (let i = 0; i < cmd.count; i++) {
        ws.send(JSON.stringify({ op: 'subscribe', subscriptions: [{ id: 100000 + i, channelId: cmd.first + i }] }));
      }
      return emit({ event: 'sent', count: cmd.count });
    }
    case 'pause':
      return ws._socket.pause();
    case 'resume':
      return ws._socket.resume();
    case 'close':
      return client.close();
    default:
      return emit({ event: 'fail', message: `unknown command ${cmd.cmd}` });
  }
}

readline.createInterface({ input: process.stdin }).on('line', (line) => {
  if (!line.trim()) return;
  try {
    handle(JSON.parse(line));
  } catch (e) {
    emit({ event: 'fail', message: String(e.stack || e) });
  }
});
process.stdin.on('end', () => process.exit(0));
