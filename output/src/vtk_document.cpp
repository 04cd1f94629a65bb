#include "vtk_document.hpp"

#include <cstring>

#include "fsi/common/error.hpp"

namespace fsi::output::detail {

VtkDocument::VtkDocument(std::string_view dataset_type) {
  xml_ = "<?xml version=\"1.0\"?>\n";
  open("VTKFile", "type=\"" + std::string(dataset_type) +
                      "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\"");
  open(dataset_type);
}

void VtkDocument::indent() {
  xml_.append(2 * open_elements_.size(), ' ');
}

void VtkDocument::open(std::string_view element, std::string_view attributes) {
  indent();
  xml_ += '<';
  xml_ += element;
  if (!attributes.empty()) {
    xml_ += ' ';
    xml_ += attributes;
  }
  xml_ += ">\n";
  open_elements_.emplace_back(element);
}

void VtkDocument::close() {
  FSI_ASSERT(!open_elements_.empty(), "close() without an open element");
  const std::string element = std::move(open_elements_.back());
  open_elements_.pop_back();
  indent();
  xml_ += "</" + element + ">\n";
}

void VtkDocument::data_array_bytes(std::string_view name, std::string_view type, int components,
                                   const std::string& extra_attributes,
                                   std::span<const std::byte> bytes) {
  indent();
  xml_ += "<DataArray type=\"" + std::string(type) + "\" Name=\"" + std::string(name) + "\"";
  if (components != 1) xml_ += " NumberOfComponents=\"" + std::to_string(components) + "\"";
  xml_ += extra_attributes;
  xml_ += " format=\"appended\" offset=\"" + std::to_string(appended_.size()) + "\"/>\n";
  const std::uint64_t size = bytes.size();
  char header[sizeof size];
  std::memcpy(header, &size, sizeof size);
  appended_.append(header, sizeof header);
  appended_.append(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

void VtkDocument::field_strings(std::string_view name, const std::vector<std::string>& values) {
  indent();
  xml_ += "<Array type=\"String\" Name=\"" + std::string(name) + "\" NumberOfTuples=\"" +
          std::to_string(values.size()) + "\" format=\"ascii\">\n";
  indent();
  for (const auto& value : values) {
    for (unsigned char c : value)
      xml_ += std::to_string(static_cast<unsigned>(c)) + ' ';
    xml_ += "0 ";
  }
  xml_ += "\n";
  indent();
  xml_ += "</Array>\n";
}

std::string VtkDocument::finish() {
  // Close everything but VTKFile, then the appended block, then VTKFile.
  while (open_elements_.size() > 1)
    close();
  xml_ += "  <AppendedData encoding=\"raw\">\n   _";
  xml_ += appended_;
  xml_ += "\n  </AppendedData>\n";
  close();
  return std::move(xml_);
}

std::vector<double> to_three_components(std::span<const double> values, int dimension) {
  FSI_ASSERT(dimension == 2 || dimension == 3, "dimension must be 2 or 3");
  const std::size_t count = values.size() / static_cast<std::size_t>(dimension);
  std::vector<double> out(3 * count, 0.0);
  for (std::size_t i = 0; i < count; ++i) {
    for (int k = 0; k < dimension; ++k)
      out[3 * i + static_cast<std::size_t>(k)] =
          values[static_cast<std::size_t>(dimension) * i + static_cast<std::size_t>(k)];
  }
  return out;
}

}  // namespace fsi::output::detail
