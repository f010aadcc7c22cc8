#!/usr/bin/env node
// Conformance helper for tests/base/mavlink/node_mavlink_test.cpp.
//
//   node check.js JOB.json OUT.json      (node-mavlink found through NODE_PATH)
//
// For every case of the job (one message with given field values, and the frame hitl
// encoded for it) this script, using only the independent npm package node-mavlink:
//   1. decodes hitl's frame (stream splitter with CRC check, packet parser, class
//      deserializer) and reports every field value it got;
//   2. encodes the same field values itself (protocol v2, same seq/sysid/compid) and
//      returns the frame in hex;
//   3. optionally signs that frame with a given key/link/timestamp, and checks the
//      signature of a frame hitl signed.
// Values travel as the little-endian hex of their wire bytes, so 64-bit integers and
// float bit patterns (-0, subnormals) survive JSON unchanged. Converting between those
// bytes and JavaScript values is done here with plain Buffer calls, not with
// node-mavlink's serializers, so the package is only used for what is under test.
'use strict';

const fs = require('fs');
const { Readable } = require('stream');
const mavlink = require('node-mavlink');

// Dialects hitl compiles in (tools/gen_messages.py: minimal, standard, common, development).
const DIALECTS = ['minimal', 'standard', 'common', 'development'];

function buildClassIndex() {
  const byName = new Map();
  for (const dialect of DIALECTS) {
    const mod = mavlink[dialect];
    if (!mod) throw new Error(`mavlink-mappings has no dialect '${dialect}'`);
    for (const value of Object.values(mod)) {
      if (typeof value !== 'function' || !Array.isArray(value.FIELDS) || typeof value.MSG_NAME !== 'string') continue;
      if (!value.MSG_NAME) continue;
      const list = byName.get(value.MSG_NAME) || [];
      if (!list.includes(value)) list.push(value);
      byName.set(value.MSG_NAME, list);
    }
  }
  return byName;
}

const SIZE = { char: 1, int8_t: 1, uint8_t: 1, int16_t: 2, uint16_t: 2, int32_t: 4, uint32_t: 4,
  int64_t: 8, uint64_t: 8, float: 4, double: 8 };

// node-mavlink spells some types specially ('uint8_t_mavlink_version', 'char[]').
function baseType(type) {
  const t = type.endsWith('[]') ? type.slice(0, -2) : type;
  return t === 'uint8_t_mavlink_version' ? 'uint8_t' : t;
}

// Reads one element from wire bytes into the JavaScript type node-mavlink uses for it.
function readElement(type, buf, off) {
  switch (type) {
    case 'char': return String.fromCharCode(buf.readUInt8(off));
    case 'int8_t': return buf.readInt8(off);
    case 'uint8_t': return buf.readUInt8(off);
    case 'int16_t': return buf.readInt16LE(off);
    case 'uint16_t': return buf.readUInt16LE(off);
    case 'int32_t': return buf.readInt32LE(off);
    case 'uint32_t': return buf.readUInt32LE(off);
    case 'int64_t': return buf.readBigInt64LE(off);
    case 'uint64_t': return buf.readBigUInt64LE(off);
    case 'float': return buf.readFloatLE(off);
    case 'double': return buf.readDoubleLE(off);
    default: throw new Error(`unknown type ${type}`);
  }
}

// Writes one element strictly: a value of the wrong JavaScript type is an error, not a conversion.
function writeElement(type, value, buf, off) {
  const int = (lo, hi) => {
    if (typeof value !== 'number' || !Number.isInteger(value) || value < lo || value > hi) {
      throw new Error(`expected an integer in [${lo}, ${hi}], got ${typeof value} ${String(value)}`);
    }
  };
  switch (type) {
    case 'char':
      if (typeof value === 'string' && value.length === 1) return buf.writeUInt8(value.charCodeAt(0) & 0xff, off);
      int(0, 255); return buf.writeUInt8(value, off);
    case 'int8_t': int(-128, 127); return buf.writeInt8(value, off);
    case 'uint8_t': int(0, 255); return buf.writeUInt8(value, off);
    case 'int16_t': int(-32768, 32767); return buf.writeInt16LE(value, off);
    case 'uint16_t': int(0, 65535); return buf.writeUInt16LE(value, off);
    case 'int32_t': int(-2147483648, 2147483647); return buf.writeInt32LE(value, off);
    case 'uint32_t': int(0, 4294967295); return buf.writeUInt32LE(value, off);
    case 'int64_t':
      if (typeof value !== 'bigint') throw new Error(`expected a BigInt, got ${typeof value}`);
      return buf.writeBigInt64LE(value, off);
    case 'uint64_t':
      if (typeof value !== 'bigint') throw new Error(`expected a BigInt, got ${typeof value}`);
      return buf.writeBigUInt64LE(value, off);
    case 'float':
      if (typeof value !== 'number') throw new Error(`expected a number, got ${typeof value}`);
      return buf.writeFloatLE(value, off);
    case 'double':
      if (typeof value !== 'number') throw new Error(`expected a number, got ${typeof value}`);
      return buf.writeDoubleLE(value, off);
    default: throw new Error(`unknown type ${type}`);
  }
}

// hex of a field's wire bytes -> the JavaScript value node-mavlink expects for the field.
function valueFromHex(type, length, hex) {
  const buf = Buffer.from(hex, 'hex');
  if (type === 'char' && length > 0) {
    const end = buf.indexOf(0);
    return buf.subarray(0, end < 0 ? buf.length : end).toString('latin1');
  }
  if (length === 0) return readElement(type, buf, 0);
  const out = [];
  for (let i = 0; i < length; i++) out.push(readElement(type, buf, i * SIZE[type]));
  return out;
}

// A decoded value -> hex of the field's wire bytes (char arrays zero-padded), checked strictly.
function hexFromValue(type, length, value) {
  const size = SIZE[type] * (length === 0 ? 1 : length);
  const buf = Buffer.alloc(size);
  if (type === 'char' && length > 0) {
    if (typeof value !== 'string') throw new Error(`expected a string, got ${typeof value}`);
    if (value.length > length) throw new Error(`string of ${value.length} chars for char[${length}]`);
    for (let i = 0; i < value.length; i++) {
      const code = value.charCodeAt(i);
      if (code > 255) throw new Error(`char code ${code} does not fit a byte`);
      buf.writeUInt8(code, i);
    }
  } else if (length === 0) {
    writeElement(type, value, buf, 0);
  } else {
    if (!Array.isArray(value) || value.length !== length) {
      throw new Error(`expected an array of ${length}, got ${Array.isArray(value) ? value.length : typeof value}`);
    }
    for (let i = 0; i < length; i++) writeElement(type, value[i], buf, i * SIZE[type]);
  }
  return buf.toString('hex');
}

// Runs bytes through node-mavlink's own stream pipeline (splitter + packet parser).
function splitPackets(bytes) {
  return new Promise((resolve, reject) => {
    const packets = [];
    const crcErrors = [];
    const stream = mavlink.createMavLinkStream(Readable.from([bytes]), {
      onCrcError: (buffer) => crcErrors.push(Buffer.from(buffer).toString('hex')),
    });
    stream.on('data', (packet) => packets.push(packet));
    stream.on('end', () => resolve({ packets, crcErrors }));
    stream.on('error', reject);
  });
}

function compareLayout(job, clazz, errors) {
  const nodeFields = new Map(clazz.FIELDS.map((f) => [f.source, f]));
  const missing = [];
  for (const f of job.fields) {
    const nf = nodeFields.get(f.name);
    if (!nf) { missing.push(f.name); continue; }
    if (baseType(nf.type) !== f.type) errors.push(`field ${f.name}: node type ${nf.type}, hitl ${f.type}`);
    if ((nf.length || 0) !== f.length) errors.push(`field ${f.name}: node length ${nf.length}, hitl ${f.length}`);
    if (nf.offset !== f.offset) errors.push(`field ${f.name}: node offset ${nf.offset}, hitl ${f.offset}`);
    if (!!nf.extension !== f.extension) errors.push(`field ${f.name}: node extension ${nf.extension}, hitl ${f.extension}`);
  }
  const hitlNames = new Set(job.fields.map((f) => f.name));
  const extra = clazz.FIELDS.map((f) => f.source).filter((n) => !hitlNames.has(n));
  if (missing.length) errors.push(`fields hitl has and node-mavlink lacks: ${missing.join(', ')}`);
  if (extra.length) errors.push(`fields node-mavlink has and hitl lacks: ${extra.join(', ')}`);
  if (clazz.MSG_ID !== job.msgid) errors.push(`node MSG_ID ${clazz.MSG_ID}, hitl ${job.msgid}`);
  if (clazz.MAGIC_NUMBER !== job.crc_extra) errors.push(`node MAGIC_NUMBER ${clazz.MAGIC_NUMBER}, hitl CRC_EXTRA ${job.crc_extra}`);
  if (clazz.PAYLOAD_LENGTH !== job.max_length) errors.push(`node PAYLOAD_LENGTH ${clazz.PAYLOAD_LENGTH}, hitl ${job.max_length}`);
}

async function decode(bytes, clazz, job) {
  const out = { frames: 0, crc_errors: 0, fields: {}, field_errors: {} };
  const { packets, crcErrors } = await splitPackets(bytes);
  out.frames = packets.length;
  out.crc_errors = crcErrors.length;
  if (packets.length !== 1) return out;
  const p = packets[0];
  out.header = {
    magic: p.buffer[0], msgid: p.header.msgid, seq: p.header.seq, sysid: p.header.sysid,
    compid: p.header.compid, payload_length: p.header.payloadLength, signed: p.signature !== null,
  };
  if (p.signature && job.sign) out.signature_ok = p.signature.matches(Buffer.from(job.sign.key, 'hex'));
  const data = p.protocol.data(p.payload, clazz);
  for (const f of job.fields) {
    const nf = clazz.FIELDS.find((x) => x.source === f.name);
    if (!nf) continue;
    try {
      out.fields[f.name] = hexFromValue(f.type, f.length, data[nf.name]);
    } catch (e) {
      out.field_errors[f.name] = e.message;
    }
  }
  return out;
}

function instance(clazz, job) {
  const msg = new clazz();
  for (const f of job.fields) {
    const nf = clazz.FIELDS.find((x) => x.source === f.name);
    if (nf) msg[nf.name] = valueFromHex(f.type, f.length, f.hex);
  }
  return msg;
}

async function runCase(job, classes) {
  const result = { name: job.name, errors: [] };
  const candidates = classes.get(job.msgname) || [];
  if (candidates.length === 0) {
    // Report what node-mavlink does know, so the test can tell a missing message from a bug.
    result.missing_class = true;
    result.magic_known = mavlink.MSG_ID_MAGIC_NUMBER[job.msgid] !== undefined;
    try {
      const { packets, crcErrors } = await splitPackets(Buffer.from(job.hitl_frame, 'hex'));
      result.decoded = { frames: packets.length, crc_errors: crcErrors.length };
    } catch (e) {
      result.errors.push(`splitting hitl's frame threw: ${e.stack || e}`);
    }
    return result;
  }
  const clazz = candidates.find((c) => c.MSG_ID === job.msgid) || candidates[0];
  result.class = clazz.name;
  result.node_fields = clazz.FIELDS.map((f) => `${f.source}->${f.name}`);
  compareLayout(job, clazz, result.errors);

  try {
    result.decoded = await decode(Buffer.from(job.hitl_frame, 'hex'), clazz, job);
    if (job.hitl_signed_frame) result.decoded_signed = await decode(Buffer.from(job.hitl_signed_frame, 'hex'), clazz, job);
  } catch (e) {
    result.errors.push(`decoding hitl's frame threw: ${e.stack || e}`);
  }

  try {
    const protocol = new mavlink.MavLinkProtocolV2(job.sysid, job.compid);
    result.node_frame = protocol.serialize(instance(clazz, job), job.seq).toString('hex');
    if (job.sign) {
      const signer = new mavlink.MavLinkProtocolV2(job.sysid, job.compid, mavlink.MavLinkProtocolV2.IFLAG_SIGNED);
      const unsigned = signer.serialize(instance(clazz, job), job.seq);
      const signed = signer.sign(unsigned, job.sign.link_id, Buffer.from(job.sign.key, 'hex'), job.sign.timestamp_ms);
      result.node_signed_frame = signed.toString('hex');
    }
  } catch (e) {
    result.errors.push(`encoding with node-mavlink threw: ${e.stack || e}`);
  }
  return result;
}

async function main() {
  const [jobPath, outPath] = process.argv.slice(2);
  if (!jobPath || !outPath) {
    process.stderr.write('usage: node check.js JOB.json OUT.json\n');
    process.exit(2);
  }
  const job = JSON.parse(fs.readFileSync(jobPath, 'utf8'));
  const classes = buildClassIndex();
  const pkg = require('node-mavlink/package.json');
  const mappings = require('mavlink-mappings/package.json');
  const results = [];
  for (const c of job.cases) results.push(await runCase(c, classes));
  fs.writeFileSync(outPath, JSON.stringify({
    node_mavlink_version: pkg.version, mavlink_mappings_version: mappings.version, node_version: process.version,
    cases: results,
  }, null, 1));
}

main().catch((e) => {
  process.stderr.write(`check.js: ${e.stack || e}\n`);
  process.exit(1);
});
