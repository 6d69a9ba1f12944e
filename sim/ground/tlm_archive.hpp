// The ground's telemetry archive: every packet received, stored raw and
// decoded (the `petra tlm --json` object) with its receive time (ground
// clock) and spacecraft time, in an SQLite file that outlives the process.
// Queries by time range, APID and event severity; CSV export; the raw
// packets of a stored pass can be sent again (replay). Schema and use in
// docs/ops.md "Telemetry archive".
//
// Inserts are grouped in transactions of up to kBatchPackets packets or
// kBatchSeconds, whichever comes first; flush() (and the destructor) commit.
// One archive object per thread; SQLite's WAL mode lets a reader (petra
// archive query) run beside a writer (petra gnd serve).
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "algo/core/result.hpp"
#include "tlm/telemetry.hpp"

struct sqlite3;
struct sqlite3_stmt;

namespace petra::ground {

struct ArchiveQuery {
  bool by_receive_time = false;  // false: the time range is spacecraft time
  double from_s = -1e300;        // inclusive, seconds (UNIX time for receive time)
  double to_s = 1e300;           // inclusive
  int apid = -1;                 // -1: every APID
  int min_severity = -1;         // >= 0: EVENT packets of this severity or above only
  long limit = -1;               // -1: no limit; rows in receive order
};

struct ArchivedPacket {
  std::int64_t id = 0;
  double receive_s = 0;  // ground clock, UNIX seconds
  double scet_s = 0;     // spacecraft time, seconds.micros
  int apid = 0;
  std::string packet;  // name: HK, EVENT, ...
  int seq = 0;
  int severity = -1;  // EVENT only
  std::vector<std::uint8_t> raw;
  std::string decoded;  // JSON
};

class TlmArchive {
 public:
  static constexpr int kBatchPackets = 512;
  static constexpr double kBatchSeconds = 0.5;

  // Opens (creating when absent) the archive file.
  static Result<std::unique_ptr<TlmArchive>> open(const std::string& path);
  ~TlmArchive();
  TlmArchive(const TlmArchive&) = delete;
  TlmArchive& operator=(const TlmArchive&) = delete;

  // Stores one received packet: its bytes as received and their decoding.
  Status add(std::span<const std::uint8_t> raw, const tlm::TmPacket& decoded, double receive_s);
  // Commits what add() stored since the last commit.
  Status flush();

  // Packets matching q, in receive order; `each` sees them one by one.
  Status query(const ArchiveQuery& q, const std::function<void(const ArchivedPacket&)>& each);
  // Packets per APID matching q.
  Result<std::map<int, long>> count_by_apid(const ArchiveQuery& q);
  // CSV: one header line, then one line per packet (the decoded JSON quoted).
  Status export_csv(const ArchiveQuery& q, std::FILE* out);

  const std::string& path() const { return path_; }

 private:
  TlmArchive() = default;
  Status exec(const char* sql);
  Error sql_error(const char* what) const;
  Status prepare_select(const ArchiveQuery& q, const char* columns, const char* tail,
                        sqlite3_stmt** stmt);

  sqlite3* db_ = nullptr;
  sqlite3_stmt* insert_ = nullptr;
  std::string path_;
  int pending_ = 0;
  double batch_started_ = 0;
};

// The ground clock as UNIX seconds (receive times).
double unix_now_s();

}  // namespace petra::ground
