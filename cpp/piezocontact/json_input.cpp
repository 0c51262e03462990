#include "json_input.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>

namespace piezocontact
{
namespace
{
[[noreturn]] void fail(const std::string& source, const std::string& what)
{
  throw ConfigError(printable(source, 200) + ": " + what);
}

/// "line L column C" of byte offset `at` (0-based), as Python's json says it
std::string position(const std::string& text, std::size_t at)
{
  at = std::min(at, text.size());
  const std::size_t line = 1 + std::count(text.begin(), text.begin() + at, '\n');
  const std::size_t bol = at ? text.rfind('\n', at - 1) : std::string::npos;
  const std::size_t col = bol == std::string::npos ? at + 1 : at - bol;
  return "line " + std::to_string(line) + " column " + std::to_string(col);
}

/// nlohmann's message without its "[json.exception...] " prefix
std::string reason(const json::exception& e)
{
  std::string what = e.what();
  const auto end = what.find("] ");
  what = end == std::string::npos ? what : what.substr(end + 2);
  if (const auto at = what.find(": "); what.rfind("parse error at", 0) == 0 and at != std::string::npos)
    what = what.substr(at + 2);
  return what;
}
/// The key path ("mesh.n", "probes.0") of the value being read when a SAX
/// parse stops: where the DOM parser's errors are only a byte offset
class KeyPath : public json::json_sax_t
{
public:
  std::string path() const
  {
    std::string out;
    for (std::size_t i = 0; i < _frames.size(); ++i)
    {
      const Frame& f = _frames[i];
      // in the innermost array, the failing element is the one after the
      // last read; outer arrays are at the element that holds it
      const long index = f.index + (i + 1 == _frames.size() ? 1 : 0);
      out += (out.empty() ? "" : ".") + (f.array ? std::to_string(index) : f.key);
    }
    return out;
  }
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(false); }
  bool key(string_t& k) override
  {
    _frames.back().key = k;
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(true); }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t position, const std::string&, const json::exception&) override
  {
    error_at = position;
    return false;
  }
  /// the byte count read when the parse stopped (1-based), 0 if it did not
  std::size_t error_at = 0;

private:
  struct Frame
  {
    bool array;
    long index = -1;
    std::string key;
  };
  bool value()
  {
    if (!_frames.empty() and _frames.back().array)
      ++_frames.back().index;
    return true;
  }
  bool open(bool array)
  {
    value();
    _frames.push_back({array, -1, ""});
    return _frames.size() <= static_cast<std::size_t>(max_json_depth);
  }
  bool close()
  {
    _frames.pop_back();
    return true;
  }
  std::vector<Frame> _frames;
};

/// The key path at which `text` stops parsing ("" at the top level) and
/// the byte count read then
std::pair<std::string, std::size_t> key_path_of_error(const std::string& text)
{
  KeyPath sax;
  json::sax_parse(text, &sax, json::input_format_t::json, false);
  return {sax.path(), sax.error_at};
}
} // namespace

std::string printable(const std::string& text, std::size_t max)
{
  std::string out;
  for (const unsigned char c : text)
  {
    if (c >= 0x20 and c < 0x7f)
      out += static_cast<char>(c);
    else
    {
      char buf[8];
      std::snprintf(buf, sizeof(buf), "\\x%02x", c);
      out += buf;
    }
    if (out.size() > max)
      return out.substr(0, max > 3 ? max - 3 : 0) + "...";
  }
  return out;
}

std::string printable(const json& value, std::size_t max)
{
  return printable(value.dump(-1, ' ', false, json::error_handler_t::replace), max);
}

json parse_json(const std::string& text, const std::string& source, std::size_t max_bytes)
{
  if (text.size() > max_bytes)
    fail(source, std::to_string(text.size()) + " bytes: more than the "
                     + std::to_string(max_bytes) + " accepted");
  const json::parser_callback_t depth_limit
      = [](int depth, json::parse_event_t, json&)
  {
    if (depth > max_json_depth)
      throw std::length_error("nested more than " + std::to_string(max_json_depth)
                              + " levels deep");
    return true;
  };
  try
  {
    return json::parse(text, depth_limit);
  }
  catch (const json::parse_error& e)
  {
    fail(source, "invalid JSON at " + position(text, e.byte ? e.byte - 1 : 0) + ": "
                     + printable(reason(e), 160));
  }
  catch (const json::out_of_range& e)
  {
    // number overflow parsing 'TOKEN': find the token for its position
    std::string what = reason(e);
    const auto q0 = what.find('\''), q1 = what.rfind('\'');
    const std::string token
        = q0 != std::string::npos and q1 > q0 ? what.substr(q0 + 1, q1 - q0 - 1) : "";
    const auto [key, read] = key_path_of_error(text);
    // the token is what was read last: it starts where it ends minus its length
    const std::size_t at = read >= token.size() and read > 0 ? read - token.size()
                                                               : std::string::npos;
    fail(source, (key.empty() ? std::string() : printable(key, 120) + " = ")
                     + printable(token, 40) + ": beyond the range of a double (invalid JSON"
                     + (at == std::string::npos ? std::string() : " at " + position(text, at))
                     + ")");
  }
  catch (const std::length_error& e)
  {
    fail(source, std::string("invalid JSON: ") + e.what());
  }
  catch (const json::exception& e)
  {
    fail(source, "invalid JSON: " + printable(reason(e), 160));
  }
}

json read_json_file(const std::filesystem::path& path, std::size_t max_bytes)
{
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec)
    fail(path.string(), "cannot read: " + ec.message());
  if (!std::filesystem::is_regular_file(status))
    fail(path.string(), "cannot read: not a regular file");
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec and size > max_bytes)
    fail(path.string(), std::to_string(size) + " bytes: more than the "
                            + std::to_string(max_bytes) + " accepted");
  std::ifstream file(path, std::ios::binary);
  if (!file)
    fail(path.string(), "cannot read: " + std::string(std::strerror(errno)));
  std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (file.bad())
    fail(path.string(), "cannot read: " + std::string(std::strerror(errno)));
  return parse_json(text, path.string(), max_bytes);
}
} // namespace piezocontact
