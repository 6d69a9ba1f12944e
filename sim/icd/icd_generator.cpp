#include "sim/icd/icd_generator.hpp"

#include <cstdio>
#include <sstream>

#include "algo/wire/ccsds.hpp"
#include "cmd/commands.hpp"
#include "cmd/param_defs.hpp"
#include "tlm/event_defs.hpp"
#include "tlm/telemetry.hpp"

namespace petra::icd {

namespace {

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.15g", v);
  return buf;
}

std::string hex(unsigned v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof(buf), "0x%0*X", digits, v);
  return buf;
}

std::string modes_of(std::uint32_t mask) {
  std::string s;
#define PETRA_MODE_LIST(NAME, value, desc) \
  if (mask & (1u << value)) {              \
    if (!s.empty()) s += ", ";             \
    s += #NAME;                            \
  }
  PETRA_MODES(PETRA_MODE_LIST)
#undef PETRA_MODE_LIST
  return s;
}

// A description as the start of a sentence.
std::string sentence(const char* text) {
  std::string s = text;
  if (!s.empty() && s[0] >= 'a' && s[0] <= 'z') s[0] = static_cast<char>(s[0] - 'a' + 'A');
  return s;
}

std::string type_cell(const wire::FieldDesc& f) {
  std::string t = wire::type_name(f.type);
  if (f.count > 1) t += "[" + std::to_string(f.count) + "]";
  return t;
}

void field_table(std::ostringstream& o, std::span<const wire::FieldDesc> fields,
                 std::size_t offset) {
  if (fields.empty()) {
    o << "No arguments.\n\n";
    return;
  }
  o << "| offset | field | type | unit | range | meaning |\n|---|---|---|---|---|---|\n";
  for (const wire::FieldDesc& f : fields) {
    o << "| " << offset << " | `" << f.name << "` | " << type_cell(f) << " | "
      << (f.unit[0] ? f.unit : "-") << " | " << num(f.min) << " .. " << num(f.max) << " | "
      << f.description << " |\n";
    offset += wire::type_bytes(f.type) * f.count;
  }
  o << "\n";
}

}  // namespace

std::string markdown_section() {
  std::ostringstream o;
  o << kBeginMarker << "\n\n";
  o << "### Framing\n\n"
    << "CCSDS space packets (CCSDS 133.0-B-2) over UDP, one packet per datagram, big-endian.\n"
    << "Primary header (6 bytes): version 0 (3 bits), type (1 bit: 1 telecommand, 0 telemetry),\n"
    << "secondary header flag 1, APID (11 bits), sequence flags (2 bits: 3 unsegmented; product\n"
    << "chunks 1 first, 0 continuation, 2 last), sequence count (14 bits, per APID, wrapping),\n"
    << "data length (16 bits: packet bytes - 7). CRC-16-CCITT: polynomial 0x1021, initial 0xFFFF,\n"
    << "no reflection, no final XOR (check value of \"123456789\": 0x29B1).\n\n"
    << "Telecommand packet (APID " << hex(cmd::kCommandApid, 3) << ", " << cmd::kMinCommandBytes
    << ".." << cmd::kMaxCommandBytes << " bytes):\n\n"
    << "| offset | bytes | field |\n|---|---|---|\n"
    << "| 0 | 6 | primary header |\n| 6 | 1 | function code |\n| 7 | 1 | spare, 0 |\n"
    << "| 8 | 4 | command counter (u32): must exceed the last authenticated one |\n"
    << "| 12 | n | arguments of the function code (below) |\n"
    << "| 12+n | 32 | HMAC-SHA256 over bytes 0..12+n with the 32-byte uplink key |\n"
    << "| 44+n | 2 | CRC-16-CCITT over bytes 0..44+n |\n\n"
    << "Validation order (first failure is the reason): size, primary header, length field, CRC,\n"
    << "HMAC, counter, function code, argument length, argument ranges, argument consistency,\n"
    << "mode. Once the HMAC verifies and the counter is fresh, the counter is used up even if a\n"
    << "later check rejects the command, so an authentic command cannot be replayed later.\n\n"
    << "Telemetry packet (" << tlm::kTmHeaderBytes + tlm::kTmCrcBytes << " + fields bytes, at most "
    << tlm::kMaxTmBytes << "):\n\n"
    << "| offset | bytes | field |\n|---|---|---|\n"
    << "| 0 | 6 | primary header |\n| 6 | 4 | time, seconds (u32, Unix time) |\n"
    << "| 10 | 4 | time, microseconds (u32) |\n| 14 | n | fields of the APID (below) |\n"
    << "| 14+n | 2 | CRC-16-CCITT over bytes 0..14+n |\n\n";

  o << "### Modes\n\n| value | mode | meaning |\n|---|---|---|\n";
#define PETRA_MODE_ROW(NAME, value, desc) o << "| " << value << " | " #NAME " | " << desc << " |\n";
  PETRA_MODES(PETRA_MODE_ROW)
#undef PETRA_MODE_ROW
  o << "\n";

  o << "### Telecommands\n\n";
  for (const cmd::CommandDesc& c : cmd::command_table()) {
    o << "#### " << c.name << " (function code " << hex(c.code, 2) << ")\n\n"
      << sentence(c.description) << ". Allowed in: " << modes_of(c.allowed_modes) << ". Packet "
      << cmd::kTcOverheadBytes + c.arg_bytes << " bytes.\n\n";
    field_table(o, c.fields, cmd::kTcHeaderBytes);
  }

  o << "### Reason codes (ACK `reason`)\n\n| code | reason | meaning |\n|---|---|---|\n";
#define PETRA_REASON_ROW(NAME, code, desc) o << "| " << code << " | " #NAME " | " << desc << " |\n";
  PETRA_REJECT_REASONS(PETRA_REASON_ROW)
  PETRA_FAIL_REASONS(PETRA_REASON_ROW)
#undef PETRA_REASON_ROW
  o << "\nCodes 1-31 come with a REJECTED ack (nothing changed); 32 and above with a FAILED ack\n"
    << "after ACCEPTED.\n\n";

  o << "### Telemetry packets\n\n";
  for (const tlm::TmDesc& t : tlm::telemetry_table()) {
    o << "#### " << t.name << " (APID " << hex(t.apid, 3) << ")\n\n"
      << sentence(t.description) << ". Packet "
      << tlm::kTmHeaderBytes + t.payload_bytes + tlm::kTmCrcBytes << " bytes.\n\n";
    field_table(o, t.fields, tlm::kTmHeaderBytes);
  }

  o << "### Events (EVENT `event_id`)\n\n| id | event | severity | text |\n|---|---|---|---|\n";
  for (const EventDesc& e : kEventTable)
    o << "| " << hex(e.id, 3) << " | " << e.name << " | " << severity_name(e.severity) << " | "
      << e.text << " |\n";
  o << "\n`{n}` is argument n; `{n:kind}` is printed by ground tools as the name of a mode, "
       "reason,\n"
    << "function code (fc), error code (errc), component, parameter or pipeline step.\n\n";

  o << "### Parameters (SET_PARAM, GET_PARAM, DUMP_PARAMS)\n\n"
    << "| id | parameter | unit | range | default | whole | meaning "
       "|\n|---|---|---|---|---|---|---|\n";
  for (const ParamDesc& p : param_table())
    o << "| " << p.id << " | " << p.name << " | " << p.unit << " | " << num(p.min) << " .. "
      << num(p.max) << " | " << num(p.default_value) << " | " << (p.integer ? "yes" : "no") << " | "
      << p.description << " |\n";
  o << "\n" << kEndMarker << "\n";
  return o.str();
}

namespace {

std::string xml_escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    if (c == '&')
      r += "&amp;";
    else if (c == '<')
      r += "&lt;";
    else if (c == '>')
      r += "&gt;";
    else if (c == '"')
      r += "&quot;";
    else
      r += c;
  }
  return r;
}

// One XTCE type element for a field (parameter or argument flavour).
void xtce_type(std::ostringstream& o, const std::string& name, const wire::FieldDesc& f,
               const char* flavour, bool ranges) {
  const bool is_float = f.type == wire::FieldType::f32 || f.type == wire::FieldType::f64;
  const bool is_signed = f.type == wire::FieldType::i16 || f.type == wire::FieldType::i32;
  const std::size_t bits = wire::type_bytes(f.type) * 8;
  const std::string unit = f.unit[0] ? std::string("<xtce:UnitSet><xtce:Unit>") +
                                           xml_escape(f.unit) + "</xtce:Unit></xtce:UnitSet>"
                                     : std::string("<xtce:UnitSet/>");
  const std::string scalar = f.count > 1 ? name + "_Element" : name;
  if (is_float) {
    o << "      <xtce:Float" << flavour << "Type name=\"" << scalar << "\" sizeInBits=\"" << bits
      << "\">" << unit << "<xtce:FloatDataEncoding sizeInBits=\"" << bits
      << "\" encoding=\"IEEE754_1985\"/>";
  } else {
    o << "      <xtce:Integer" << flavour << "Type name=\"" << scalar << "\" signed=\""
      << (is_signed ? "true" : "false") << "\" sizeInBits=\"" << bits << "\">" << unit
      << "<xtce:IntegerDataEncoding sizeInBits=\"" << bits << "\" encoding=\""
      << (is_signed ? "twosComplement" : "unsigned") << "\"/>";
  }
  if (ranges) {
    if (is_float)
      o << "<xtce:ValidRange minInclusive=\"" << num(f.min) << "\" maxInclusive=\"" << num(f.max)
        << "\"/>";
    else
      o << "<xtce:ValidRangeSet><xtce:ValidRange minInclusive=\"" << num(f.min)
        << "\" maxInclusive=\"" << num(f.max) << "\"/></xtce:ValidRangeSet>";
  }
  o << "</xtce:" << (is_float ? "Float" : "Integer") << flavour << "Type>\n";
  if (f.count > 1)
    o << "      <xtce:Array" << flavour << "Type name=\"" << name << "\" arrayTypeRef=\"" << scalar
      << "\"><xtce:DimensionList><xtce:Dimension><xtce:StartingIndex><xtce:FixedValue>0</"
         "xtce:FixedValue>"
      << "</xtce:StartingIndex><xtce:EndingIndex><xtce:FixedValue>" << f.count - 1
      << "</xtce:FixedValue></xtce:EndingIndex></xtce:Dimension></xtce:DimensionList></xtce:Array"
      << flavour << "Type>\n";
}

wire::FieldDesc header_field(const char* name, std::size_t bits) {
  // Integer fields of the CCSDS header, described with the widest type that holds them.
  wire::FieldDesc f;
  f.name = name;
  f.type = bits <= 8    ? wire::FieldType::u8
           : bits <= 16 ? wire::FieldType::u16
                        : wire::FieldType::u32;
  return f;
}

void header_types(std::ostringstream& o, const char* flavour) {
  const struct {
    const char* name;
    int bits;
  } h[] = {{"CCSDS_Version", 3}, {"CCSDS_Type", 1},     {"CCSDS_SecHdrFlag", 1},
           {"CCSDS_APID", 11},   {"CCSDS_SeqFlags", 2}, {"CCSDS_SeqCount", 14},
           {"CCSDS_Length", 16}};
  for (const auto& x : h)
    o << "      <xtce:Integer" << flavour << "Type name=\"" << x.name << "_Type\" signed=\"false\">"
      << "<xtce:UnitSet/><xtce:IntegerDataEncoding sizeInBits=\"" << x.bits
      << "\" encoding=\"unsigned\"/></xtce:Integer" << flavour << "Type>\n";
  (void)header_field;
}

}  // namespace

std::string xtce_document() {
  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<!-- Generated by `petra icd` from cmd/ and tlm/: do not edit by hand. -->\n"
    << "<xtce:SpaceSystem name=\"Petra\" xmlns:xtce=\"http://www.omg.org/spec/XTCE/20180204\">\n"
    << "  <xtce:TelemetryMetaData>\n    <xtce:ParameterTypeSet>\n";
  header_types(o, "Parameter");
  o << "      <xtce:IntegerParameterType name=\"U32_Type\" signed=\"false\"><xtce:UnitSet/>"
       "<xtce:IntegerDataEncoding sizeInBits=\"32\" "
       "encoding=\"unsigned\"/></xtce:IntegerParameterType>\n"
    << "      <xtce:IntegerParameterType name=\"U16_Type\" signed=\"false\"><xtce:UnitSet/>"
       "<xtce:IntegerDataEncoding sizeInBits=\"16\" "
       "encoding=\"unsigned\"/></xtce:IntegerParameterType>\n";
  for (const tlm::TmDesc& t : tlm::telemetry_table())
    for (const wire::FieldDesc& f : t.fields)
      xtce_type(o, std::string(t.name) + "." + f.name + "_Type", f, "Parameter", false);
  o << "    </xtce:ParameterTypeSet>\n    <xtce:ParameterSet>\n";
  for (const char* p : {"CCSDS_Version", "CCSDS_Type", "CCSDS_SecHdrFlag", "CCSDS_APID",
                        "CCSDS_SeqFlags", "CCSDS_SeqCount", "CCSDS_Length"})
    o << "      <xtce:Parameter name=\"" << p << "\" parameterTypeRef=\"" << p << "_Type\"/>\n";
  o << "      <xtce:Parameter name=\"TM_Seconds\" parameterTypeRef=\"U32_Type\"/>\n"
    << "      <xtce:Parameter name=\"TM_Micros\" parameterTypeRef=\"U32_Type\"/>\n"
    << "      <xtce:Parameter name=\"TM_CRC\" parameterTypeRef=\"U16_Type\"/>\n";
  for (const tlm::TmDesc& t : tlm::telemetry_table())
    for (const wire::FieldDesc& f : t.fields)
      o << "      <xtce:Parameter name=\"" << t.name << "." << f.name << "\" parameterTypeRef=\""
        << t.name << "." << f.name << "_Type\" shortDescription=\"" << xml_escape(f.description)
        << "\"/>\n";
  o << "    </xtce:ParameterSet>\n    <xtce:ContainerSet>\n"
    << "      <xtce:SequenceContainer name=\"CCSDS_TM\" abstract=\"true\"><xtce:EntryList>\n";
  for (const char* p :
       {"CCSDS_Version", "CCSDS_Type", "CCSDS_SecHdrFlag", "CCSDS_APID", "CCSDS_SeqFlags",
        "CCSDS_SeqCount", "CCSDS_Length", "TM_Seconds", "TM_Micros"})
    o << "        <xtce:ParameterRefEntry parameterRef=\"" << p << "\"/>\n";
  o << "      </xtce:EntryList></xtce:SequenceContainer>\n";
  for (const tlm::TmDesc& t : tlm::telemetry_table()) {
    o << "      <xtce:SequenceContainer name=\"" << t.name << "\" shortDescription=\""
      << xml_escape(t.description) << "\"><xtce:EntryList>\n";
    for (const wire::FieldDesc& f : t.fields)
      o << "        <xtce:ParameterRefEntry parameterRef=\"" << t.name << "." << f.name << "\"/>\n";
    o << "        <xtce:ParameterRefEntry parameterRef=\"TM_CRC\"/>\n"
      << "      </xtce:EntryList><xtce:BaseContainer "
         "containerRef=\"CCSDS_TM\"><xtce:RestrictionCriteria>"
      << "<xtce:ComparisonList><xtce:Comparison parameterRef=\"CCSDS_APID\" value=\"" << t.apid
      << "\"/></xtce:ComparisonList></xtce:RestrictionCriteria></xtce:BaseContainer></"
         "xtce:SequenceContainer>\n";
  }
  o << "    </xtce:ContainerSet>\n  </xtce:TelemetryMetaData>\n"
    << "  <xtce:CommandMetaData>\n    <xtce:ArgumentTypeSet>\n";
  header_types(o, "Argument");
  o << "      <xtce:IntegerArgumentType name=\"FunctionCode_Type\" signed=\"false\"><xtce:UnitSet/>"
       "<xtce:IntegerDataEncoding sizeInBits=\"8\" "
       "encoding=\"unsigned\"/></xtce:IntegerArgumentType>\n"
    << "      <xtce:IntegerArgumentType name=\"Counter_Type\" signed=\"false\"><xtce:UnitSet/>"
       "<xtce:IntegerDataEncoding sizeInBits=\"32\" "
       "encoding=\"unsigned\"/></xtce:IntegerArgumentType>\n"
    << "      <xtce:BinaryArgumentType name=\"HMAC_Type\"><xtce:UnitSet/><xtce:BinaryDataEncoding>"
       "<xtce:SizeInBits><xtce:FixedValue>256</xtce:FixedValue></xtce:SizeInBits></"
       "xtce:BinaryDataEncoding>"
       "</xtce:BinaryArgumentType>\n"
    << "      <xtce:IntegerArgumentType name=\"CRC_Type\" signed=\"false\"><xtce:UnitSet/>"
       "<xtce:IntegerDataEncoding sizeInBits=\"16\" "
       "encoding=\"unsigned\"/></xtce:IntegerArgumentType>\n";
  for (const cmd::CommandDesc& c : cmd::command_table())
    for (const wire::FieldDesc& f : c.fields)
      xtce_type(o, std::string(c.name) + "." + f.name + "_Type", f, "Argument", true);
  o << "    </xtce:ArgumentTypeSet>\n    <xtce:MetaCommandSet>\n"
    << "      <xtce:MetaCommand name=\"CCSDS_TC\" abstract=\"true\"><xtce:ArgumentList>\n";
  for (const char* p : {"CCSDS_Version", "CCSDS_Type", "CCSDS_SecHdrFlag", "CCSDS_APID",
                        "CCSDS_SeqFlags", "CCSDS_SeqCount", "CCSDS_Length"})
    o << "        <xtce:Argument name=\"" << p << "\" argumentTypeRef=\"" << p << "_Type\"/>\n";
  o << "        <xtce:Argument name=\"FunctionCode\" argumentTypeRef=\"FunctionCode_Type\"/>\n"
    << "        <xtce:Argument name=\"Counter\" argumentTypeRef=\"Counter_Type\"/>\n"
    << "      </xtce:ArgumentList><xtce:CommandContainer "
       "name=\"CCSDS_TC_Header\"><xtce:EntryList>\n";
  for (const char* p : {"CCSDS_Version", "CCSDS_Type", "CCSDS_SecHdrFlag", "CCSDS_APID",
                        "CCSDS_SeqFlags", "CCSDS_SeqCount", "CCSDS_Length"})
    o << "        <xtce:ArgumentRefEntry argumentRef=\"" << p << "\"/>\n";
  o << "        <xtce:ArgumentRefEntry argumentRef=\"FunctionCode\"/>\n"
    << "        <xtce:FixedValueEntry binaryValue=\"00\" sizeInBits=\"8\"/>\n"
    << "        <xtce:ArgumentRefEntry argumentRef=\"Counter\"/>\n"
    << "      </xtce:EntryList></xtce:CommandContainer></xtce:MetaCommand>\n";
  for (const cmd::CommandDesc& c : cmd::command_table()) {
    o << "      <xtce:MetaCommand name=\"" << c.name << "\" shortDescription=\""
      << xml_escape(c.description) << "\"><xtce:BaseMetaCommand metaCommandRef=\"CCSDS_TC\">"
      << "<xtce:ArgumentAssignmentList>"
      << "<xtce:ArgumentAssignment argumentName=\"CCSDS_Type\" argumentValue=\"1\"/>"
      << "<xtce:ArgumentAssignment argumentName=\"CCSDS_SecHdrFlag\" argumentValue=\"1\"/>"
      << "<xtce:ArgumentAssignment argumentName=\"CCSDS_APID\" argumentValue=\""
      << cmd::kCommandApid << "\"/>"
      << "<xtce:ArgumentAssignment argumentName=\"CCSDS_SeqFlags\" argumentValue=\"3\"/>"
      << "<xtce:ArgumentAssignment argumentName=\"CCSDS_Length\" argumentValue=\""
      << cmd::kTcOverheadBytes + c.arg_bytes - 7 << "\"/>"
      << "<xtce:ArgumentAssignment argumentName=\"FunctionCode\" argumentValue=\""
      << unsigned{c.code}
      << "\"/></xtce:ArgumentAssignmentList></xtce:BaseMetaCommand>\n        <xtce:ArgumentList>\n";
    for (const wire::FieldDesc& f : c.fields)
      o << "          <xtce:Argument name=\"" << f.name << "\" argumentTypeRef=\"" << c.name << "."
        << f.name << "_Type\" shortDescription=\"" << xml_escape(f.description) << "\"/>\n";
    o << "          <xtce:Argument name=\"HMAC\" argumentTypeRef=\"HMAC_Type\"/>\n"
      << "          <xtce:Argument name=\"CRC\" argumentTypeRef=\"CRC_Type\"/>\n"
      << "        </xtce:ArgumentList>\n        <xtce:CommandContainer name=\"" << c.name
      << "_Container\"><xtce:EntryList>\n";
    for (const wire::FieldDesc& f : c.fields)
      o << "          <xtce:ArgumentRefEntry argumentRef=\"" << f.name << "\"/>\n";
    o << "          <xtce:ArgumentRefEntry argumentRef=\"HMAC\"/>\n"
      << "          <xtce:ArgumentRefEntry argumentRef=\"CRC\"/>\n"
      << "        </xtce:EntryList><xtce:BaseContainer containerRef=\"CCSDS_TC_Header\"/>"
      << "</xtce:CommandContainer>\n      </xtce:MetaCommand>\n";
  }
  o << "    </xtce:MetaCommandSet>\n  </xtce:CommandMetaData>\n</xtce:SpaceSystem>\n";
  return o.str();
}

std::string extract_section(const std::string& doc) {
  const auto b = doc.find(kBeginMarker);
  const auto e = doc.find(kEndMarker);
  if (b == std::string::npos || e == std::string::npos || e < b) return "";
  return doc.substr(b, e - b + std::string(kEndMarker).size()) + "\n";
}

std::string splice_section(const std::string& doc, const std::string& section) {
  const auto b = doc.find(kBeginMarker);
  const auto e = doc.find(kEndMarker);
  if (b == std::string::npos || e == std::string::npos || e < b) {
    std::string out = doc;
    if (!out.empty() && out.back() != '\n') out += "\n";
    return out + "\n## Telecommand and telemetry packets\n\n" + section;
  }
  std::size_t tail = e + std::string(kEndMarker).size();
  if (tail < doc.size() && doc[tail] == '\n') ++tail;
  return doc.substr(0, b) + section + doc.substr(tail);
}

}  // namespace petra::icd
