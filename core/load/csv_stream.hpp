#pragma once
// CSV records pulled from a byte stream in chunks, for files too big to hold: a GTFS
// stop_times.txt may be 200 MB, inflated from a zip entry as it is read.
//
// Why not CsvReader (csv.hpp): it parses a string_view over the whole text, so the text must be
// in memory first. This reader pulls 64 KiB at a time from a ByteSource and keeps only the
// current record. The dialect is the same (RFC 4180: quoted fields with commas, doubled quotes
// and line breaks; CRLF or LF; a UTF-8 BOM; blank lines skipped; every row as many fields as the
// header), and so are the per-record limits (max_csv_fields, max_csv_field_bytes). A stream is
// also bounded as a whole: at most `max_bytes` bytes and `max_rows` records (blank ones
// included), the limits named by the caller, so that a small zip cannot inflate into an endless
// file. Polls util::check_stop() every 4,096 records.
//
// Rows are numbered as GTFS validators number them: the header is row 1, so row N is line N of a
// file without line breaks inside quotes.

#include "load/import_limits.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tourmap::load {

// Where the bytes come from: a file, a zip entry.
class ByteSource {
 public:
  virtual ~ByteSource() = default;
  // Reads up to `size` bytes into `buffer`; 0 at the end. Throws LoadError when it cannot read.
  virtual std::size_t read(char* buffer, std::size_t size) = 0;
};

// The byte and row bounds of one stream, with the names of the limits they come from.
struct CsvStreamBounds {
  std::uint64_t max_bytes = UINT64_MAX;
  std::string_view bytes_limit = "max_bytes";
  std::uint64_t max_rows = UINT64_MAX;
  std::string_view rows_limit = "max_rows";
};

class CsvStream {
 public:
  // Reads the header (the first non-blank record). Throws LoadError "<source>: empty file (no
  // header)" on an empty stream, LimitExceeded beyond the limits.
  CsvStream(ByteSource& in, std::string source, const ImportLimits& limits, CsvStreamBounds bounds = {});

  const std::string& source() const { return source_; }
  const std::vector<std::string>& header() const { return header_; }
  // Index of the column named `name` (case-insensitive, spaces around header names ignored).
  std::optional<std::size_t> find_column(std::string_view name) const;
  // Same; throws LoadError "<source>: missing column <name>".
  std::size_t column(std::string_view name) const;

  // Reads the next row; false at the end. Throws LoadError on an unterminated quote or a row
  // whose field count differs from the header's, LimitExceeded beyond a limit.
  bool next();
  // Field `c` of the current row (c < header().size()).
  std::string_view field(std::size_t c) const { return fields_[c]; }
  // Field `c`, or "" when the column is absent.
  std::string_view field(const std::optional<std::size_t>& c) const {
    return c ? std::string_view(fields_[*c]) : std::string_view();
  }
  // Row number of the current row (the header is row 1).
  std::size_t row() const { return row_; }
  // "<source> row N" for errors about the current row.
  std::string where() const;
  // Rows read so far, header excluded.
  std::size_t rows_read() const { return rows_read_; }

 private:
  // Reads one record into fields_[0, count_) (false at the end); `blank` tells an empty line.
  bool read_record(bool& blank);
  // The next byte, or -1 at the end of the stream.
  int get();
  int peek();
  bool fill();
  void count_bytes(std::size_t n);  // bytes read: max_bytes; 0 marks the end
  void end_field();
  void push(std::string& field, char ch);

  ByteSource& in_;
  std::string source_;
  std::size_t max_fields_, max_field_bytes_;
  CsvStreamBounds bounds_;
  std::vector<char> buffer_;
  std::size_t pos_ = 0, end_ = 0;
  std::uint64_t bytes_ = 0, records_ = 0;
  bool eof_ = false;
  std::size_t row_ = 0, rows_read_ = 0;
  std::vector<std::string> header_;
  std::vector<std::string> fields_;  // reused between rows: their capacity stays
  std::size_t count_ = 0;            // fields of the current record
};

}  // namespace tourmap::load
