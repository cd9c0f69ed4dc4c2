#include "load/csv_stream.hpp"

#include "load/csv.hpp"
#include "load/load_error.hpp"
#include "util/stop.hpp"

namespace tourmap::load {
namespace {

constexpr std::size_t kChunk = 64 * 1024;

}  // namespace

CsvStream::CsvStream(ByteSource& in, std::string source, const ImportLimits& limits, CsvStreamBounds bounds)
    : in_(in),
      source_(std::move(source)),
      max_fields_(limits.max_csv_fields),
      max_field_bytes_(limits.max_csv_field_bytes),
      bounds_(bounds),
      buffer_(kChunk) {
  // A UTF-8 BOM before the header (a source may hand out fewer bytes than asked: read on
  // until three are in, or the end).
  while (end_ < 3 && !eof_) {
    const std::size_t n = in_.read(buffer_.data() + end_, buffer_.size() - end_);
    count_bytes(n);
    end_ += n;
  }
  if (end_ >= 3 && std::string_view(buffer_.data(), 3) == "\xEF\xBB\xBF") pos_ = 3;
  bool blank = false;
  while (read_record(blank)) {
    if (blank) continue;
    header_.assign(fields_.begin(), fields_.begin() + static_cast<std::ptrdiff_t>(count_));
    return;
  }
  throw LoadError(source_, "empty file (no header)");
}

std::optional<std::size_t> CsvStream::find_column(std::string_view name) const {
  const std::string_view names[] = {name};
  return find_csv_column(header_, names);
}

std::size_t CsvStream::column(std::string_view name) const {
  if (auto c = find_column(name)) return *c;
  throw LoadError(source_, "missing column " + std::string(name));
}

std::string CsvStream::where() const { return source_ + " row " + std::to_string(row_); }

void CsvStream::count_bytes(std::size_t n) {
  bytes_ += n;
  if (bytes_ > bounds_.max_bytes) check_limit(bytes_, bounds_.max_bytes, bounds_.bytes_limit, source_, "bytes");
  if (n == 0) eof_ = true;
}

bool CsvStream::fill() {
  if (eof_) return false;
  pos_ = 0;
  end_ = in_.read(buffer_.data(), buffer_.size());
  count_bytes(end_);
  return end_ > 0;
}

int CsvStream::peek() {
  if (pos_ == end_ && !fill()) return -1;
  return static_cast<unsigned char>(buffer_[pos_]);
}

int CsvStream::get() {
  const int ch = peek();
  if (ch >= 0) ++pos_;
  return ch;
}

// Ends field count_ and starts the next (which must fit max_csv_fields).
void CsvStream::end_field() {
  ++count_;
  if (count_ + 1 > max_fields_) check_limit(count_ + 1, max_fields_, "max_csv_fields", where(), "fields in a row");
  if (count_ >= fields_.size()) fields_.emplace_back();
  fields_[count_].clear();
}

void CsvStream::push(std::string& field, char ch) {
  if (field.size() >= max_field_bytes_)
    check_limit(field.size() + 1, max_field_bytes_, "max_csv_field_bytes", where(),
                "bytes in field " + std::to_string(count_ + 1));
  field.push_back(ch);
}

bool CsvStream::next() {
  bool blank = false;
  while (read_record(blank)) {
    if (blank) continue;
    ++rows_read_;
    if (count_ != header_.size())
      throw LoadError(where(), "expected " + std::to_string(header_.size()) + " fields, found " +
                                   std::to_string(count_));
    return true;
  }
  return false;
}

// The fields of the record are fields_[0, count_); fields_[count_] is the one being read (kept
// allocated, so rows of a long file reuse their strings' capacity).
bool CsvStream::read_record(bool& blank) {
  blank = false;
  count_ = 0;
  if (fields_.empty()) fields_.emplace_back();
  fields_[0].clear();
  if (peek() < 0) return false;
  ++records_;
  row_ = records_;
  if (records_ > bounds_.max_rows) check_limit(records_, bounds_.max_rows, bounds_.rows_limit, source_, "rows");
  if ((records_ & 4095) == 1) util::check_stop();  // the first record, then every 4,096

  bool in_quotes = false, field_started = false, any_in_record = false;
  for (int ch = get(); ch >= 0; ch = get()) {
    std::string& field = fields_[count_];
    if (in_quotes) {
      if (ch == '"') {
        if (peek() == '"') {
          push(field, '"');
          get();
        } else {
          in_quotes = false;
        }
      } else {
        push(field, static_cast<char>(ch));
      }
      continue;
    }
    switch (ch) {
      case '"':
        if (!field_started || field.empty()) {
          in_quotes = true;
          field_started = true;
          any_in_record = true;
        } else {
          push(field, '"');  // a stray quote inside an unquoted field is kept literally
        }
        break;
      case ',':
        end_field();  // may reallocate fields_: `field` is bound anew for the next byte
        field_started = false;
        any_in_record = true;
        break;
      case '\r':
        break;
      case '\n':
        blank = count_ == 0 && field.empty() && !any_in_record;
        ++count_;
        return true;
      default:
        push(field, static_cast<char>(ch));
        field_started = true;
        any_in_record = true;
    }
  }
  if (in_quotes) throw LoadError(where(), "unterminated quoted field");
  blank = count_ == 0 && fields_[0].empty() && !any_in_record;
  ++count_;
  return true;
}

}  // namespace tourmap::load
