#include "io/rosbag2/db3_reader.hpp"

#include <fmt/format.h>
#include <sqlite3.h>

#include <algorithm>
#include <map>
#include <memory>

#include "common/errors.hpp"

namespace dsswarm::rosbag2 {
namespace {

struct CloseDatabase {
  void operator()(sqlite3* db) const { sqlite3_close(db); }
};
using Database = std::unique_ptr<sqlite3, CloseDatabase>;

// One query; every SQLite error becomes an InputError naming the file.
class Query {
 public:
  Query(sqlite3* db, const std::string& sql, const std::string& file) : db_(db), file_(file) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &statement_, nullptr) != SQLITE_OK) {
      fail("not a rosbag2 SQLite database");
    }
  }
  ~Query() { sqlite3_finalize(statement_); }
  Query(const Query&) = delete;
  Query& operator=(const Query&) = delete;

  bool next_row() {
    const int rc = sqlite3_step(statement_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    fail("cannot read the database");
  }
  std::int64_t integer(int column) const { return sqlite3_column_int64(statement_, column); }
  std::string text(int column) const {
    const unsigned char* t = sqlite3_column_text(statement_, column);
    return t == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(t));
  }
  std::span<const std::uint8_t> blob(int column) const {
    const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(statement_, column));
    const auto size = static_cast<std::size_t>(sqlite3_column_bytes(statement_, column));
    return data == nullptr ? std::span<const std::uint8_t>() : std::span(data, size);
  }

 private:
  [[noreturn]] void fail(const char* what) const {
    throw InputError(fmt::format("{}: {} (SQLite: {})", file_, what, sqlite3_errmsg(db_)));
  }

  sqlite3* db_;
  const std::string& file_;
  sqlite3_stmt* statement_ = nullptr;
};

// Topics by id, with their message counts.
std::map<std::int64_t, StorageTopic> read_topics(sqlite3* db, const std::string& file) {
  std::map<std::int64_t, StorageTopic> topics;
  Query rows(db, "SELECT id, name, type, serialization_format FROM topics", file);
  while (rows.next_row()) {
    topics[rows.integer(0)] = StorageTopic{rows.text(1), rows.text(2), rows.text(3), 0};
  }
  Query counts(db, "SELECT topic_id, COUNT(*) FROM messages GROUP BY topic_id", file);
  while (counts.next_row()) {
    const auto it = topics.find(counts.integer(0));
    if (it != topics.end()) it->second.messages = static_cast<std::size_t>(counts.integer(1));
  }
  return topics;
}

// SQLite reads the pages a query needs only, so a cut-off file can look
// fine; its header says how long it should be.
void check_length(sqlite3* db, const std::string& file, std::uint64_t file_bytes) {
  Query pages(db, "PRAGMA page_count", file);
  Query page_size(db, "PRAGMA page_size", file);
  if (!pages.next_row() || !page_size.next_row()) return;
  const auto expected = static_cast<std::uint64_t>(pages.integer(0) * page_size.integer(0));
  if (file_bytes < expected) {
    throw InputError(fmt::format("{}: truncated: its header says {} pages of {} bytes, the file "
                                 "has {} bytes",
                                 file, pages.integer(0), page_size.integer(0), file_bytes));
  }
}

// Hands over the wanted messages of an open rosbag2 database; returns its topics.
std::vector<StorageTopic> read_database(sqlite3* db, const std::string& file,
                                        std::uint64_t file_bytes, const TopicFilter& wanted,
                                        const MessageHandler& on_message) {
  check_length(db, file, file_bytes);
  const std::map<std::int64_t, StorageTopic> topics = read_topics(db, file);
  std::string wanted_ids;
  for (const auto& [id, topic] : topics) {
    if (!wanted(topic.name)) continue;
    if (!wanted_ids.empty()) wanted_ids.push_back(',');
    wanted_ids.append(std::to_string(id));
  }
  if (!wanted_ids.empty()) {
    // Row ids grow in the order rosbag2 wrote the messages: the file order.
    Query rows(db,
               "SELECT topic_id, timestamp, data FROM messages WHERE topic_id IN (" + wanted_ids +
                   ") ORDER BY id",
               file);
    while (rows.next_row()) {
      const StorageTopic& topic = topics.at(rows.integer(0));
      on_message(StoredMessage{topic, rows.integer(1), rows.blob(2)});
    }
  }
  std::vector<StorageTopic> sorted;
  for (const auto& [id, topic] : topics) sorted.push_back(topic);
  std::sort(sorted.begin(), sorted.end(),
            [](const StorageTopic& a, const StorageTopic& b) { return a.name < b.name; });
  return sorted;
}

}  // namespace

std::vector<StorageTopic> read_db3_file(const std::filesystem::path& path,
                                        const TopicFilter& wanted,
                                        const MessageHandler& on_message) {
  const std::string file = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(file + ": no such file");
  sqlite3* raw = nullptr;
  const int rc = sqlite3_open_v2(file.c_str(), &raw, SQLITE_OPEN_READONLY, nullptr);
  const Database db(raw);
  if (rc != SQLITE_OK) {
    throw InputError(fmt::format("{}: cannot open as SQLite database ({})", file,
                                 raw != nullptr ? sqlite3_errmsg(raw) : sqlite3_errstr(rc)));
  }
  return read_database(db.get(), file, std::filesystem::file_size(path, ec), wanted, on_message);
}

std::vector<StorageTopic> read_db3_bytes(std::span<std::uint8_t> bytes, const std::string& name,
                                         const TopicFilter& wanted,
                                         const MessageHandler& on_message) {
  sqlite3* raw = nullptr;
  const int rc = sqlite3_open_v2(":memory:", &raw, SQLITE_OPEN_READWRITE, nullptr);
  const Database db(raw);
  if (rc != SQLITE_OK) throw std::bad_alloc();
  // The buffer outlives the connection, which only reads it.
  if (sqlite3_deserialize(db.get(), "main", bytes.data(), static_cast<sqlite3_int64>(bytes.size()),
                          static_cast<sqlite3_int64>(bytes.size()),
                          SQLITE_DESERIALIZE_READONLY) != SQLITE_OK) {
    throw InputError(fmt::format("{}: cannot open as SQLite database ({})", name,
                                 sqlite3_errmsg(db.get())));
  }
  return read_database(db.get(), name, bytes.size(), wanted, on_message);
}

}  // namespace dsswarm::rosbag2
