#!/usr/bin/env python3
"""Generate base/mavlink/messages.h from the official MAVLink XML definitions.

A developer tool, not a build step: the build uses the committed header and never
needs the XML. Run it again when a message is added to MESSAGES below:

    tools/gen_messages.py ../shared/mavlink/development.xml > base/mavlink/messages.h

Field order on the wire follows the MAVLink rule: base fields sorted by element
size, largest first (stable), extension fields after them in XML order. CRC_EXTRA
is computed from the base fields as the MAVLink generator does; the conformance
tests check both against the XML and against node-mavlink.
"""
import os
import sys
import xml.etree.ElementTree as ET

MESSAGES = [
    "HEARTBEAT", "SYS_STATUS", "SYSTEM_TIME", "PING", "PARAM_REQUEST_READ",
    "PARAM_REQUEST_LIST", "PARAM_VALUE", "PARAM_SET", "GPS_RAW_INT", "SCALED_IMU",
    "SCALED_PRESSURE", "ATTITUDE", "ATTITUDE_QUATERNION", "LOCAL_POSITION_NED",
    "GLOBAL_POSITION_INT", "RC_CHANNELS", "MANUAL_CONTROL", "RC_CHANNELS_OVERRIDE",
    "VFR_HUD", "COMMAND_INT", "COMMAND_LONG", "COMMAND_ACK", "SET_ATTITUDE_TARGET",
    "ATTITUDE_TARGET", "SET_POSITION_TARGET_LOCAL_NED", "POSITION_TARGET_LOCAL_NED",
    "HIL_ACTUATOR_CONTROLS", "HIGHRES_IMU", "HIL_SENSOR", "TIMESYNC", "HIL_GPS",
    "HIL_STATE_QUATERNION", "SERIAL_CONTROL", "BATTERY_STATUS", "AUTOPILOT_VERSION",
    "ESTIMATOR_STATUS", "VIBRATION", "HOME_POSITION", "MESSAGE_INTERVAL",
    "EXTENDED_SYS_STATE", "NAMED_VALUE_FLOAT", "NAMED_VALUE_INT", "STATUSTEXT",
    "ODOMETRY", "ACTUATOR_OUTPUT_STATUS", "EVENT", "DISTANCE_SENSOR",
]

SIZES = {"char": 1, "uint8_t": 1, "int8_t": 1, "uint16_t": 2, "int16_t": 2,
         "uint32_t": 4, "int32_t": 4, "float": 4, "uint64_t": 8, "int64_t": 8,
         "double": 8}


def x25(data, crc=0xFFFF):
    for b in data:
        tmp = b ^ (crc & 0xFF)
        tmp = (tmp ^ (tmp << 4)) & 0xFF
        crc = ((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4)) & 0xFFFF
    return crc


def load(path, seen=None):
    seen = set() if seen is None else seen
    path = os.path.abspath(path)
    if path in seen:
        return {}
    seen.add(path)
    root = ET.parse(path).getroot()
    msgs = {}
    for inc in root.findall("include"):
        msgs.update(load(os.path.join(os.path.dirname(path), inc.text.strip()), seen))
    for m in root.iter("message"):
        fields, ext = [], False
        for el in m:
            if el.tag == "extensions":
                ext = True
            elif el.tag == "field":
                t = el.get("type")
                n = 0
                if "[" in t:
                    t, n = t[:-1].split("[")
                    n = int(n)
                wire_t = "uint8_t" if t == "uint8_t_mavlink_version" else t
                fields.append(dict(name=el.get("name"), type=wire_t, n=n, ext=ext,
                                   units=el.get("units") or "",
                                   enum=el.get("enum") or "",
                                   desc=" ".join((el.text or "").split())))
        msgs[m.get("name")] = dict(id=int(m.get("id")), name=m.get("name"), fields=fields,
                                   desc=" ".join((m.findtext("description") or "").split()))
    return msgs


def wire_order(fields):
    base = [f for f in fields if not f["ext"]]
    ext = [f for f in fields if f["ext"]]
    return sorted(base, key=lambda f: -SIZES[f["type"]]) + ext


def crc_extra(msg):
    crc = x25((msg["name"] + " ").encode())
    for f in wire_order(msg["fields"]):
        if f["ext"]:
            continue
        crc = x25((f["type"] + " ").encode(), crc)
        crc = x25((f["name"] + " ").encode(), crc)
        if f["n"]:
            crc = x25(bytes([f["n"]]), crc)
    return (crc & 0xFF) ^ (crc >> 8)


def camel(name):
    return "".join(p.capitalize() for p in name.split("_"))


def cxx_type(f):
    if f["n"]:
        return "std::array<%s, %d>" % (f["type"], f["n"])
    return f["type"]


def length(fields):
    return sum(SIZES[f["type"]] * max(1, f["n"]) for f in fields)


def offsets(msg):
    """Payload offset of each field in wire order."""
    out, at = {}, 0
    for f in wire_order(msg["fields"]):
        out[f["name"]] = at
        at += SIZES[f["type"]] * max(1, f["n"])
    return out


def check_entry(msg):
    """msg::kStandardChecks' row: id, CRC_EXTRA, lengths, target flags and offsets (as mavgen's
    mavlink_msg_entry_t; MANUAL_CONTROL names its system in `target`, as the router reads it)."""
    ofs = offsets(msg)
    system = "target_system" if "target_system" in ofs else ("target" if "target" in ofs else None)
    flags = (1 if system else 0) | (2 if "target_component" in ofs else 0)
    base = [f for f in msg["fields"] if not f["ext"]]
    return "{%d, %d, %d, %d, %d, %d, %d}" % (
        msg["id"], crc_extra(msg), length(base), length(msg["fields"]), flags,
        ofs[system] if system else 0, ofs.get("target_component", 0))


def main():
    msgs = load(sys.argv[1])
    out = []
    w = out.append
    w("// Generated by tools/gen_messages.py from the official MAVLink XML definitions")
    w("// (message_definitions/v1.0: minimal, standard, common, development). Do not edit by hand.")
    w("#pragma once")
    w("")
    w("#include <array>")
    w("#include <cstdint>")
    w("#include <string_view>")
    w("#include <tuple>")
    w("")
    w('#include "base/mavlink/field_ref.h"')
    w('#include "base/mavlink/message_check.h"')
    w("")
    w("namespace hitl::mavlink::msg {")
    for name in MESSAGES:
        m = msgs[name]
        cls = camel(name)
        fields = m["fields"]
        base = [f for f in fields if not f["ext"]]
        w("")
        w("/// %s (#%d): %s" % (name, m["id"], m["desc"][:300]))
        w("struct %s {" % cls)
        w("  static constexpr uint32_t kId = %d;" % m["id"])
        w('  static constexpr std::string_view kName = "%s";' % name)
        w("  static constexpr uint8_t kCrcExtra = %d;" % crc_extra(m))
        w("  static constexpr uint8_t kMinLength = %d;  // payload bytes without extensions" % length(base))
        w("  static constexpr uint8_t kMaxLength = %d;  // payload bytes with extensions" % length(fields))
        w("")
        for f in fields:
            unit = "[%s] " % f["units"] if f["units"] else ""
            w("  %s %s{};  ///< %s%s" % (cxx_type(f), f["name"], unit, f["desc"][:160]))
        w("")
        w("  /// Fields in wire order (base fields by size, then extensions).")
        w("  static constexpr auto fields() {")
        w("    return std::make_tuple(")
        wo = wire_order(fields)
        for i, f in enumerate(wo):
            sep = "," if i + 1 < len(wo) else ");"
            w('        FieldRef{"%s", &%s::%s, "%s", "%s", %s}%s' % (
                f["name"], cls, f["name"], f["units"], f["enum"],
                "true" if f["ext"] else "false", sep))
        w("  }")
        w("};")
    w("")
    w("/// Every message compiled into hitl, for registries and conformance tests.")
    w("using All = TypeList<%s>;" % ", ".join(camel(n) for n in MESSAGES))
    w("")
    w("/// Every message of the XML, typed above or not, by id: {id, CRC_EXTRA, min length, max length,")
    w("/// target flags, target_system offset, target_component offset} (message_check.h).")
    every = sorted(msgs.values(), key=lambda m: m["id"])
    w("inline constexpr std::array<MessageCheck, %d> kStandardChecks{{" % len(every))
    for m in every:
        w("    %s,  // %s" % (check_entry(m), m["name"]))
    w("}};")
    w("")
    w("}  // namespace hitl::mavlink::msg")
    print("\n".join(out))


if __name__ == "__main__":
    main()
