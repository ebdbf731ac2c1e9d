#include "data/h5_util.hpp"

#include <cmath>
#include <cstring>
#include <map>
#include <vector>

#include "ptnet/error.hpp"
#include "ptnet/strings.hpp"

namespace ptnet::h5 {

void quiet() {
  static const bool done = [] {
    H5::Exception::dontPrint();
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)done;
}

namespace {
herr_t collect_error(unsigned n, const H5E_error2_t* err, void* data) {
  auto* out = static_cast<std::vector<std::string>*>(data);
  if (err && err->desc && *err->desc) out->push_back(err->desc);
  return 0;
}
}  // namespace

std::string error_stack_text() {
  std::vector<std::string> descs;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect_error, &descs);
  std::string text;
  // Innermost (most specific) first.
  for (auto it = descs.rbegin(); it != descs.rend(); ++it) {
    if (!text.empty()) text += "; ";
    text += *it;
    if (text.size() > 200) break;
  }
  return text;
}

namespace {
constexpr std::size_t kMaxLinkValue = 4096;  // bytes of a link's target shown in a message

struct LinkVisit {
  std::map<haddr_t, std::string> named;  // objects seen, by address: their first name
  std::string problem;                   // the first link refused, described
};

// The target of soft or external link `name` (relative to `group`), read
// without traversing it; "" when it cannot be read.
std::string link_target(hid_t group, const char* name, const H5L_info_t& info) {
  if (info.u.val_size == 0 || info.u.val_size > kMaxLinkValue) return "";
  std::vector<char> buf(info.u.val_size);
  if (H5Lget_val(group, name, buf.data(), buf.size(), H5P_DEFAULT) < 0) return "";
  if (info.type == H5L_TYPE_SOFT) return std::string(buf.data(), ::strnlen(buf.data(), buf.size()));
  const char *file = nullptr, *object = nullptr;
  unsigned flags = 0;
  if (H5Lunpack_elink_val(buf.data(), buf.size(), &flags, &file, &object) < 0 || !file || !object) return "";
  return std::string(file) + ":" + object;
}

herr_t visit_link(hid_t group, const char* name, const H5L_info_t* info, void* data) {
  auto* visit = static_cast<LinkVisit*>(data);
  const std::string here = escaped("/" + std::string(name), 80, false);
  if (info->type == H5L_TYPE_HARD) {
    const auto [first, fresh] = visit->named.emplace(info->u.address, here);
    if (fresh) return 0;
    visit->problem = here + " is a second name of " + first->second;
    return 1;
  }
  const std::string kind = info->type == H5L_TYPE_SOFT       ? "a soft link"
                           : info->type == H5L_TYPE_EXTERNAL ? "an external link"
                                                             : "a user-defined link";
  const std::string target =
      info->type == H5L_TYPE_SOFT || info->type == H5L_TYPE_EXTERNAL ? link_target(group, name, *info) : "";
  visit->problem = here + " is " + kind + (target.empty() ? "" : " to " + escaped(target, 80));
  return 1;  // stop at the first
}
}  // namespace

void check_hard_links(const H5::H5File& file, const std::string& path) {
  LinkVisit visit;
  H5O_info_t root{};
  if (H5Oget_info2(file.getId(), &root, H5O_INFO_BASIC) < 0)
    throw H5::FileIException("H5Oget_info2", "cannot read the root group");
  visit.named.emplace(root.addr, "/ (the root group)");
  if (H5Lvisit(file.getId(), H5_INDEX_NAME, H5_ITER_NATIVE, visit_link, &visit) < 0)
    throw H5::FileIException("H5Lvisit", "cannot list the links of the file");
  if (!visit.problem.empty())
    throw Error::in(path, visit.problem + "; ptnet reads objects stored in the file itself, each under one name");
}

void check_local_storage(const H5::DataSet& ds, const std::string& path, const std::string& where) {
  const H5::DSetCreatPropList plist = ds.getCreatePlist();
  if (plist.getLayout() == H5D_VIRTUAL)
    throw Error::in(path, where + " is a virtual dataset (its data are in other files); a dataset holds its data "
                                  "itself (ptnet reads no other file)");
  if (H5Pget_external_count(plist.getId()) > 0) {
    char name[256] = "";
    off_t offset = 0;
    hsize_t size = 0;
    H5Pget_external(plist.getId(), 0, sizeof name, name, &offset, &size);
    name[sizeof name - 1] = '\0';
    throw Error::in(path, where + " keeps its data in the external file " + escaped(name, 80) +
                              "; a dataset holds its data itself (ptnet reads no other file)");
  }
}

H5::Group create_group(const H5::H5Location& parent, const std::string& name) {
  hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
  H5Pset_obj_track_times(gcpl, false);
  hid_t id = H5Gcreate2(parent.getId(), name.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT);
  H5Pclose(gcpl);
  if (id < 0) throw H5::GroupIException("create_group", "H5Gcreate2 failed for " + name);
  H5Gclose(id);
  return parent.openGroup(name);
}

static H5::StrType utf8_vlen() {
  H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
  type.setCset(H5T_CSET_UTF8);
  return type;
}

void write_attr(const H5::H5Object& obj, const std::string& name, const std::string& value) {
  H5::StrType type = utf8_vlen();
  H5::Attribute a = obj.createAttribute(name, type, H5::DataSpace(H5S_SCALAR));
  a.write(type, value);
}

void write_attr(const H5::H5Object& obj, const std::string& name, int value) {
  H5::Attribute a = obj.createAttribute(name, H5::PredType::STD_I32LE, H5::DataSpace(H5S_SCALAR));
  a.write(H5::PredType::NATIVE_INT, &value);
}

void write_attr(const H5::H5Object& obj, const std::string& name, double value) {
  H5::Attribute a = obj.createAttribute(name, H5::PredType::IEEE_F64LE, H5::DataSpace(H5S_SCALAR));
  a.write(H5::PredType::NATIVE_DOUBLE, &value);
}

bool has_attr(const H5::H5Object& obj, const std::string& name) {
  return obj.attrExists(name);
}

static H5::Attribute open_scalar_attr(const H5::H5Object& obj, const std::string& name,
                                      const std::string& file, const std::string& where) {
  if (!obj.attrExists(name))
    throw Error::in(file, where + ": missing attribute '" + name + "'");
  H5::Attribute a = obj.openAttribute(name);
  if (a.getSpace().getSimpleExtentNpoints() != 1)
    throw Error::in(file, where + ": attribute '" + name + "' is not a single value");
  return a;
}

std::string read_string_attr(const H5::H5Object& obj, const std::string& name,
                             const std::string& file, const std::string& where) {
  H5::Attribute a = open_scalar_attr(obj, name, file, where);
  if (a.getTypeClass() != H5T_STRING)
    throw Error::in(file, where + ": attribute '" + name + "' is not a string");
  H5::StrType type = a.getStrType();
  std::string value;
  a.read(type, value);
  while (!value.empty() && value.back() == '\0') value.pop_back();  // fixed-length padding
  if (utf8_invalid_at(value) != std::string::npos)  // what every reader of text refuses (check_utf8)
    throw Error::in(file, where + ": attribute '" + name + "' is not UTF-8: " + escaped(value, 80));
  return value;
}

double read_number_attr(const H5::H5Object& obj, const std::string& name,
                        const std::string& file, const std::string& where) {
  H5::Attribute a = open_scalar_attr(obj, name, file, where);
  H5T_class_t cls = a.getTypeClass();
  if (cls != H5T_INTEGER && cls != H5T_FLOAT)
    throw Error::in(file, where + ": attribute '" + name + "' is not a number");
  double value = 0;
  a.read(H5::PredType::NATIVE_DOUBLE, &value);
  if (!std::isfinite(value))
    throw Error::in(file, where + ": attribute '" + name + "' is not finite");
  return value;
}

long read_integer_attr(const H5::H5Object& obj, const std::string& name,
                       const std::string& file, const std::string& where) {
  H5::Attribute a = open_scalar_attr(obj, name, file, where);
  if (a.getTypeClass() != H5T_INTEGER)
    throw Error::in(file, where + ": attribute '" + name + "' is not an integer");
  long long value = 0;
  a.read(H5::PredType::NATIVE_LLONG, &value);
  return long(value);
}

}  // namespace ptnet::h5
