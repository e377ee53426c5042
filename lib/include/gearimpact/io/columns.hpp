// An output's columns described once: each column's name, unit and how to
// read its value from a row. The CSV writers write from such a table, the
// Python package makes its arrays from the same table, and the test of the
// docs compares their column lists to it (docs/usage.md, "Output columns").
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace gearimpact {

template <typename Row>
struct Column {
  std::string name;
  std::string unit;       // SI, as docs/usage.md writes it; "" for a count or a code
  bool integral = false;  // a count or a code, written as an integer
  std::function<double(const Row&)> value;
  // The member of the row that the value is, when it is one (null otherwise): a reader may view
  // such a column in place, with the row's size as its stride, instead of copying it.
  double Row::*real_member = nullptr;
  int Row::*int_member = nullptr;
  // A value that a row may lack (a pair's column where fewer pairs touch): `value` gives NaN
  // there, written as an empty field (NaN in Python's float64 array, integral or not).
  bool may_be_empty = false;
  // A column of text (a flank's name, a list of teeth) instead of a number: written as it is (no
  // comma in it), a str array in Python. `value` is then empty.
  std::function<std::string(const Row&)> text;
  // A yes or no (value 1 or 0): written true or false, a bool array in Python.
  bool boolean = false;
};

template <typename Row>
using Columns = std::vector<Column<Row>>;

// A column computed from the row: a double, or with `integral` an integer held in a double.
template <typename Row>
Column<Row> computed_column(std::string name, std::string unit,
                            std::function<double(const Row&)> value, bool integral = false) {
  Column<Row> column;
  column.name = std::move(name);
  column.unit = std::move(unit);
  column.integral = integral;
  column.value = std::move(value);
  return column;
}

// A column that is a double member of the row.
template <typename Row>
Column<Row> member_column(std::string name, std::string unit, double Row::*member) {
  Column<Row> column = computed_column<Row>(std::move(name), std::move(unit),
                                            [member](const Row& r) { return r.*member; });
  column.real_member = member;
  return column;
}

// A column that is an int member of the row (a count or a code: no unit).
template <typename Row>
Column<Row> member_column(std::string name, int Row::*member) {
  Column<Row> column = computed_column<Row>(
      std::move(name), "", [member](const Row& r) { return static_cast<double>(r.*member); }, true);
  column.int_member = member;
  return column;
}

// A computed column whose value a row may lack (NaN there): an empty field in the CSV.
template <typename Row>
Column<Row> optional_column(std::string name, std::string unit,
                            std::function<double(const Row&)> value, bool integral = false) {
  Column<Row> column =
      computed_column<Row>(std::move(name), std::move(unit), std::move(value), integral);
  column.may_be_empty = true;
  return column;
}

// A column of text, without a unit.
template <typename Row>
Column<Row> text_column(std::string name, std::function<std::string(const Row&)> text) {
  Column<Row> column;
  column.name = std::move(name);
  column.text = std::move(text);
  return column;
}

// A yes-or-no column: true or false.
template <typename Row>
Column<Row> boolean_column(std::string name, std::function<bool(const Row&)> yes) {
  Column<Row> column = computed_column<Row>(
      std::move(name), "", [yes = std::move(yes)](const Row& r) { return yes(r) ? 1.0 : 0.0; });
  column.boolean = true;
  return column;
}

// The header line of a CSV of these columns: the names, comma-separated, and "\n".
template <typename Row>
std::string csv_header(const Columns<Row>& columns) {
  std::string out;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (c > 0) out += ',';
    out += columns[c].name;
  }
  out += '\n';
  return out;
}

// A number appended to `out`: a real as "%.17g" writes it (17 significant digits, every double
// reads back exactly), an integer in full. std::to_chars with a precision is specified as printf
// with that precision in the C locale, the same bytes, and takes about half snprintf's time,
// which a series of millions of rows notices.
inline void append_real(std::string& out, double value) {
  char number[32];
  const std::to_chars_result r =
      std::to_chars(number, number + sizeof number, value, std::chars_format::general, 17);
  out.append(number, r.ptr);
}
inline void append_integer(std::string& out, long long value) {
  char number[24];
  const std::to_chars_result r = std::to_chars(number, number + sizeof number, value);
  out.append(number, r.ptr);
}

// One row appended to `out` as a CSV line: a real at 17 significant digits, an integral column
// as an integer, an empty field for a value the row lacks, a text as it is.
template <typename Row>
void append_csv_row(std::string& out, const Columns<Row>& columns, const Row& row) {
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (c > 0) out += ',';
    const Column<Row>& column = columns[c];
    if (column.text) {
      out += column.text(row);
    } else if (column.real_member != nullptr) {
      append_real(out, row.*column.real_member);
    } else if (column.int_member != nullptr) {
      append_integer(out, row.*column.int_member);
    } else {
      const double value = column.value(row);
      if (column.may_be_empty && std::isnan(value)) continue;
      if (column.boolean) {
        out += value != 0.0 ? "true" : "false";
      } else if (column.integral) {
        append_integer(out, static_cast<long long>(value));
      } else {
        append_real(out, value);
      }
    }
  }
  out += '\n';
}

// A whole CSV: the header, then a line per row.
template <typename Row>
std::string csv_of(const Columns<Row>& columns, const std::vector<Row>& rows) {
  std::string out = csv_header(columns);
  for (const Row& row : rows) append_csv_row(out, columns, row);
  return out;
}

}  // namespace gearimpact
