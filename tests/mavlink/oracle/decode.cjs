#!/usr/bin/env node
// Test oracle for swath's MAVLink codec (tests/mavlink/codec_oracle_test.cpp): what node-mavlink
// (npm, the ArduPilot organisation's; installed by scripts/setup into .oracles/) says.
//
//   node decode.cjs MODULES crc ID...          one line per id: "ID NAME CRC_EXTRA"
//   node decode.cjs MODULES frames FILE ID...  one line per frame node-mavlink accepts in FILE:
//       "VERSION SEQ SYSID COMPID MSGID", and for the ids listed " | NAME field=value ..." with the
//       MAVLink field names in wire order; char arrays up to their first NUL, arrays as [a,b].
//   node decode.cjs MODULES capture            the path of the capture node-mavlink ships
// MODULES is the node_modules folder holding node-mavlink.
'use strict'
const path = require('node:path')
const fs = require('node:fs')

const [modules, mode, ...rest] = process.argv.slice(2)
const mavlink = require(path.join(modules, 'node-mavlink'))
const REGISTRY = { ...mavlink.minimal.REGISTRY, ...mavlink.common.REGISTRY, ...mavlink.ardupilotmega.REGISTRY }

function text(v) {
  if (typeof v === 'bigint') return v.toString()
  if (typeof v === 'number') {
    if (Number.isNaN(v)) return 'nan'
    if (v === Infinity) return 'inf'
    if (v === -Infinity) return '-inf'
    return String(v)
  }
  if (typeof v === 'string') { const z = v.indexOf('\0'); return z < 0 ? v : v.slice(0, z) }
  if (Array.isArray(v)) return '[' + v.map(text).join(',') + ']'
  return String(v)
}

if (mode === 'capture') {
  console.log(path.join(modules, 'node-mavlink', 'examples', 'mavlink-v2-3412-packets.bin'))
} else if (mode === 'crc') {
  for (const id of rest.map(Number)) {
    const c = REGISTRY[id]
    console.log(c ? `${id} ${c.MSG_NAME} ${c.MAGIC_NUMBER}` : `${id} ? ?`)
  }
} else if (mode === 'frames') {
  const [file, ...ids] = rest
  const wanted = new Set(ids.map(Number))
  const stream = mavlink.createMavLinkStream(fs.createReadStream(file))
  const lines = []
  stream.on('data', packet => {
    const h = packet.header
    const version = h.magic === 0xFD ? 2 : 1
    let line = `${version} ${h.seq} ${h.sysid} ${h.compid} ${h.msgid}`
    const clazz = REGISTRY[h.msgid]
    if (wanted.has(h.msgid) && clazz) {
      const data = packet.protocol.data(packet.payload, clazz)
      line += ` | ${clazz.MSG_NAME}`
      for (const f of clazz.FIELDS) line += ` ${f.source}=${text(data[f.name])}`
    }
    lines.push(line)
  })
  stream.on('end', () => process.stdout.write(lines.join('\n') + (lines.length ? '\n' : '')))
} else {
  console.error('usage: decode.cjs MODULES crc ID... | frames FILE ID... | capture')
  process.exit(2)
}
