#pragma once
// Small helpers shared by the whitespace-separated numeric text formats
// (TUM trajectories, benchmark relation files): split a line into fields and
// parse one field as a finite number, with errors that name file, line and field.
#include <filesystem>
#include <fstream>
#include <functional>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

namespace dsswarm {

// Opens `path` for reading; throws InputError naming the file (and `what` it
// was supposed to be, e.g. "trajectory") if it is missing, a directory or unreadable.
std::ifstream open_text_input(const std::filesystem::path& path, std::string_view what);

// Drops a trailing '\r' so files written on Windows parse like any other.
std::string_view strip_carriage_return(std::string_view line);

// True for lines that carry no data: empty, only whitespace, or a '#' comment.
bool is_blank_or_comment(std::string_view line);

// Calls `on_line(line, where)` for every data line of `in` (blank lines and
// comments skipped, '\r' stripped), `where` being "source:LINE". Throws
// InputError if the stream fails while reading.
void for_each_data_line(std::istream& in, const std::string& source,
                        const std::function<void(std::string_view line, const std::string& where)>& on_line);

// Whitespace-separated tokens of `line` (views into it).
std::vector<std::string_view> split_fields(std::string_view line);
// The same into `out` (cleared first): a reader of many lines keeps one buffer.
void split_fields(std::string_view line, std::vector<std::string_view>& out);

// Parses `token` as a finite decimal number. `where` is "file:line" and
// `field` the field's name; both go into the InputError thrown on failure.
double parse_finite_field(std::string_view token, std::string_view where, std::string_view field);

}  // namespace dsswarm
