#include "sim/ground/tlm_archive.hpp"

#include <sqlite3.h>

#include <chrono>
#include <string>

#include "sim/ground/tlm_format.hpp"

namespace petra::ground {

namespace {

constexpr const char* kSchema = R"(
CREATE TABLE IF NOT EXISTS packets(
  id INTEGER PRIMARY KEY,
  receive_s REAL NOT NULL,
  scet_s REAL NOT NULL,
  apid INTEGER NOT NULL,
  packet TEXT NOT NULL,
  seq INTEGER NOT NULL,
  severity INTEGER,
  raw BLOB NOT NULL,
  decoded TEXT NOT NULL);
CREATE INDEX IF NOT EXISTS packets_scet ON packets(scet_s);
CREATE INDEX IF NOT EXISTS packets_receive ON packets(receive_s);
CREATE INDEX IF NOT EXISTS packets_apid ON packets(apid, scet_s);
)";

const char* packet_name_of(std::uint16_t apid) {
  const tlm::TmDesc* d = tlm::find_telemetry(apid);
  return d != nullptr ? d->name : "?";
}

double scet_of(const tlm::TmPacket& p) {
  return static_cast<double>(p.header.time.seconds) + 1e-6 * p.header.time.micros;
}

std::string csv_field(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace

double unix_now_s() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

Result<std::unique_ptr<TlmArchive>> TlmArchive::open(const std::string& path) {
  std::unique_ptr<TlmArchive> a(new TlmArchive());
  a->path_ = path;
  if (sqlite3_open_v2(path.c_str(), &a->db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) !=
      SQLITE_OK) {
    const std::string why = a->db_ != nullptr ? sqlite3_errmsg(a->db_) : "out of memory";
    return Error::make(Errc::io_error, "archive %s: %s", path.c_str(), why.c_str());
  }
  sqlite3_busy_timeout(a->db_, 5000);  // a reader and the station share the file
  // WAL: readers beside the writer; NORMAL: a commit survives a crash of the
  // process (not of the machine's power), at a fraction of FULL's cost.
  PETRA_TRY(a->exec("PRAGMA journal_mode=WAL; PRAGMA synchronous=NORMAL;"));
  PETRA_TRY(a->exec(kSchema));
  if (sqlite3_prepare_v2(a->db_,
                         "INSERT INTO packets(receive_s, scet_s, apid, packet, seq, severity, raw, "
                         "decoded) VALUES(?,?,?,?,?,?,?,?)",
                         -1, &a->insert_, nullptr) != SQLITE_OK)
    return a->sql_error("prepare insert");
  return a;
}

TlmArchive::~TlmArchive() {
  (void)flush();
  sqlite3_finalize(insert_);
  sqlite3_close(db_);
}

Status TlmArchive::exec(const char* sql) {
  char* msg = nullptr;
  if (sqlite3_exec(db_, sql, nullptr, nullptr, &msg) != SQLITE_OK) {
    const std::string why = msg != nullptr ? msg : sqlite3_errmsg(db_);
    sqlite3_free(msg);
    return Error::make(Errc::io_error, "archive %s: %s", path_.c_str(), why.c_str());
  }
  return {};
}

Error TlmArchive::sql_error(const char* what) const {
  return Error::make(Errc::io_error, "archive %s: %s: %s", path_.c_str(), what,
                     sqlite3_errmsg(db_));
}

Status TlmArchive::add(std::span<const std::uint8_t> raw, const tlm::TmPacket& decoded,
                       double receive_s) {
  if (pending_ == 0) {
    PETRA_TRY(exec("BEGIN"));
    batch_started_ = receive_s;
  }
  const std::string json = format_json(decoded);
  const auto apid = decoded.header.primary.apid;
  sqlite3_reset(insert_);
  sqlite3_bind_double(insert_, 1, receive_s);
  sqlite3_bind_double(insert_, 2, scet_of(decoded));
  sqlite3_bind_int(insert_, 3, apid);
  sqlite3_bind_text(insert_, 4, packet_name_of(apid), -1, SQLITE_STATIC);
  sqlite3_bind_int(insert_, 5, decoded.header.primary.seq_count);
  if (const auto* e = std::get_if<tlm::Event>(&decoded.body))
    sqlite3_bind_int(insert_, 6, e->severity);
  else
    sqlite3_bind_null(insert_, 6);
  sqlite3_bind_blob(insert_, 7, raw.data(), static_cast<int>(raw.size()), SQLITE_STATIC);
  sqlite3_bind_text(insert_, 8, json.c_str(), static_cast<int>(json.size()), SQLITE_STATIC);
  if (sqlite3_step(insert_) != SQLITE_DONE) return sql_error("insert");
  if (++pending_ >= kBatchPackets || receive_s - batch_started_ >= kBatchSeconds) return flush();
  return {};
}

Status TlmArchive::flush() {
  if (pending_ == 0) return {};
  pending_ = 0;
  return exec("COMMIT");
}

Status TlmArchive::prepare_select(const ArchiveQuery& q, const char* columns, const char* tail,
                                  sqlite3_stmt** stmt) {
  const std::string time = q.by_receive_time ? "receive_s" : "scet_s";
  std::string sql =
      std::string("SELECT ") + columns + " FROM packets WHERE " + time + " BETWEEN ?1 AND ?2";
  if (q.apid >= 0) sql += " AND apid = ?3";
  if (q.min_severity >= 0) sql += " AND severity >= ?4";
  sql += tail;
  if (q.limit >= 0) sql += " LIMIT ?5";
  if (sqlite3_prepare_v2(db_, sql.c_str(), -1, stmt, nullptr) != SQLITE_OK)
    return sql_error("query");
  sqlite3_bind_double(*stmt, 1, q.from_s);
  sqlite3_bind_double(*stmt, 2, q.to_s);
  if (q.apid >= 0) sqlite3_bind_int(*stmt, 3, q.apid);
  if (q.min_severity >= 0) sqlite3_bind_int(*stmt, 4, q.min_severity);
  if (q.limit >= 0) sqlite3_bind_int64(*stmt, 5, q.limit);
  return {};
}

Status TlmArchive::query(const ArchiveQuery& q,
                         const std::function<void(const ArchivedPacket&)>& each) {
  PETRA_TRY(flush());
  sqlite3_stmt* st = nullptr;
  PETRA_TRY(prepare_select(q, "id, receive_s, scet_s, apid, packet, seq, severity, raw, decoded",
                           " ORDER BY id", &st));
  int rc = SQLITE_ROW;
  ArchivedPacket p;
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    p.id = sqlite3_column_int64(st, 0);
    p.receive_s = sqlite3_column_double(st, 1);
    p.scet_s = sqlite3_column_double(st, 2);
    p.apid = sqlite3_column_int(st, 3);
    p.packet = reinterpret_cast<const char*>(sqlite3_column_text(st, 4));
    p.seq = sqlite3_column_int(st, 5);
    p.severity = sqlite3_column_type(st, 6) == SQLITE_NULL ? -1 : sqlite3_column_int(st, 6);
    const auto* raw = static_cast<const std::uint8_t*>(sqlite3_column_blob(st, 7));
    p.raw.assign(raw, raw + sqlite3_column_bytes(st, 7));
    p.decoded = reinterpret_cast<const char*>(sqlite3_column_text(st, 8));
    each(p);
  }
  sqlite3_finalize(st);
  if (rc != SQLITE_DONE) return sql_error("query");
  return {};
}

Result<std::map<int, long>> TlmArchive::count_by_apid(const ArchiveQuery& q) {
  PETRA_TRY(flush());
  sqlite3_stmt* st = nullptr;
  PETRA_TRY(prepare_select(q, "apid, count(*)", " GROUP BY apid", &st));
  std::map<int, long> counts;
  int rc = SQLITE_ROW;
  while ((rc = sqlite3_step(st)) == SQLITE_ROW)
    counts[sqlite3_column_int(st, 0)] = static_cast<long>(sqlite3_column_int64(st, 1));
  sqlite3_finalize(st);
  if (rc != SQLITE_DONE) return sql_error("count");
  return counts;
}

Status TlmArchive::export_csv(const ArchiveQuery& q, std::FILE* out) {
  std::fprintf(out, "receive_s,scet_s,apid,packet,seq,severity,decoded\n");
  return query(q, [out](const ArchivedPacket& p) {
    std::fprintf(out, "%.6f,%.6f,%d,%s,%d,%s,%s\n", p.receive_s, p.scet_s, p.apid, p.packet.c_str(),
                 p.seq, p.severity < 0 ? "" : std::to_string(p.severity).c_str(),
                 csv_field(p.decoded).c_str());
  });
}

}  // namespace petra::ground
