#pragma once
// Builds one VTK XML file (format 1.0, header_type UInt64, little endian) whose data arrays all
// live in a raw appended block. Each array's block is its byte count as UInt64 followed by the
// values; an array's offset attribute is where its block starts, counted from the byte after the
// '_' that opens the appended data.

#include <bit>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fsi::output::detail {

static_assert(std::endian::native == std::endian::little,
              "the VTK writer copies values as they are in memory and declares LittleEndian; "
              "a big-endian host needs byte swapping in VtkDocument::append_block");

template <class T>
constexpr std::string_view vtk_type_name();
template <>
constexpr std::string_view vtk_type_name<double>() {
  return "Float64";
}
template <>
constexpr std::string_view vtk_type_name<std::int64_t>() {
  return "Int64";
}
template <>
constexpr std::string_view vtk_type_name<std::uint8_t>() {
  return "UInt8";
}

class VtkDocument {
 public:
  // dataset_type: "UnstructuredGrid" or "PolyData".
  explicit VtkDocument(std::string_view dataset_type);

  // Opens <element attributes>; close() closes the innermost open element.
  void open(std::string_view element, std::string_view attributes = {});
  void close();

  template <class T>
  void data_array(std::string_view name, int components, std::span<const T> values) {
    data_array_bytes(name, vtk_type_name<T>(), components, "", std::as_bytes(values));
  }
  // A field-data array (NumberOfTuples instead of per-point counts).
  template <class T>
  void field_array(std::string_view name, std::span<const T> values) {
    data_array_bytes(name, vtk_type_name<T>(), 1,
                     " NumberOfTuples=\"" + std::to_string(values.size()) + "\"",
                     std::as_bytes(values));
  }
  // A field-data String array, written inline as ASCII codes, each string ended by 0 (the form
  // VTK's own writer uses; strings cannot go into the appended block as plain numbers).
  void field_strings(std::string_view name, const std::vector<std::string>& values);

  // Closes every open element, appends the data block and returns the whole file.
  std::string finish();

 private:
  void data_array_bytes(std::string_view name, std::string_view type, int components,
                        const std::string& extra_attributes, std::span<const std::byte> bytes);
  void indent();

  std::string xml_;
  std::string appended_;
  std::vector<std::string> open_elements_;
};

// Copies dimension-component vectors into 3 components (z = 0 in 2D).
std::vector<double> to_three_components(std::span<const double> values, int dimension);

}  // namespace fsi::output::detail
