#include "io/xdmf_index.h"

#include <cstdio>
#include <sstream>

namespace mpm_lig::io {
namespace {

std::string escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

//! One HDF5 dataset as an XDMF data item.
std::string hdf_item(const std::string& dims, const std::string& number_type, int precision,
                     const std::string& h5_path, const std::string& indent) {
  return indent + "<DataItem Dimensions=\"" + dims + "\" NumberType=\"" + number_type +
         "\" Precision=\"" + std::to_string(precision) + "\" Format=\"HDF\">" + escaped(h5_path) +
         "</DataItem>\n";
}

//! XDMF's Tensor6 is ordered xx xy xz yy yz zz (ParaView reads it so); the file keeps the
//! project's Voigt order xx yy zz xy xz yz. A function item joins the columns in XDMF order
//! so that ParaView labels the components right without a second copy of the data.
std::string tensor6_item(std::size_t n, const std::string& h5_path, const std::string& indent) {
  // Voigt column of each XDMF Tensor6 component.
  constexpr int kColumn[6] = {0, 3, 4, 1, 5, 2};
  const std::string rows = std::to_string(n);
  std::string out = indent +
                    "<DataItem ItemType=\"Function\" Function=\"JOIN($0, $1, $2, $3, $4, " +
                    "$5)\" Dimensions=\"" + rows + " 6\">\n";
  for (const int column : kColumn) {
    out += indent + "  <DataItem ItemType=\"HyperSlab\" Dimensions=\"" + rows + " 1\">\n";
    out += indent + "    <DataItem Dimensions=\"3 2\" Format=\"XML\">0 " + std::to_string(column) +
           " 1 1 " + rows + " 1</DataItem>\n";
    out += hdf_item(rows + " 6", "Float", 8, h5_path, indent + "    ");
    out += indent + "  </DataItem>\n";
  }
  return out + indent + "</DataItem>\n";
}

std::string attribute(const XdmfField& field, std::size_t n, const std::string& h5_path) {
  const std::string rows = std::to_string(n);
  const std::string indent = "          ";
  std::string type, item;
  switch (field.kind) {
    case XdmfKind::scalar:
      type = "Scalar";
      item = hdf_item(rows, "Float", 8, h5_path, indent);
      break;
    case XdmfKind::vector:
      type = "Vector";
      item = hdf_item(rows + " 3", "Float", 8, h5_path, indent);
      break;
    case XdmfKind::tensor:
      type = "Tensor6";
      item = tensor6_item(n, h5_path, indent);
      break;
    case XdmfKind::matrix:
      // XDMF's Tensor is row-major xx xy xz yx ... zz, the order the file keeps.
      type = "Tensor";
      item = hdf_item(rows + " 9", "Float", 8, h5_path, indent);
      break;
    case XdmfKind::integer:
      type = "Scalar";
      item = hdf_item(rows, "Int", 4, h5_path, indent);
      break;
  }
  return "        <Attribute Name=\"" + escaped(field.name) + "\" AttributeType=\"" + type +
         "\" Center=\"Node\">\n" + item + "        </Attribute>\n";
}

std::string grid(const std::string& h5_name, const XdmfStep& step) {
  const std::string base = h5_name + ":/" + step.group + "/";
  const std::string n = std::to_string(step.points);
  std::ostringstream out;
  out << "      <Grid Name=\"" << step.group << "\" GridType=\"Uniform\">\n"
      << "        <Time Value=\"" << number(step.time) << "\"/>\n"
      << "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n
      << "\" NodesPerElement=\"1\"/>\n"
      << "        <Geometry GeometryType=\"XYZ\">\n"
      << hdf_item(n + " 3", "Float", 8, base + "positions", "          ")
      << "        </Geometry>\n";
  for (const XdmfField& field : step.fields)
    out << attribute(field, step.points, base + field.name);
  out << "      </Grid>\n";
  return out.str();
}

}  // namespace

std::string xdmf_text(const std::string& h5_name, const std::vector<XdmfStep>& steps) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\" ?>\n"
      << "<Xdmf Version=\"2.0\">\n"
      << "  <Domain>\n"
      << "    <Grid Name=\"material_points\" GridType=\"Collection\" "
         "CollectionType=\"Temporal\">\n";
  for (const XdmfStep& step : steps)
    out << grid(h5_name, step);
  out << "    </Grid>\n"
      << "  </Domain>\n"
      << "</Xdmf>\n";
  return out.str();
}

}  // namespace mpm_lig::io
