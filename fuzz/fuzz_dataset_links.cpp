// libFuzzer harness: the dataset reader's link handling. The input is a
// list of edits, 4 bytes each (at most kMaxEdits), applied in memory (HDF5's
// core driver, nothing on disk) to a good dataset (tests/data/hdf5_links/
// good.h5); byte 0 picks the edit, byte 1 where (the root, /sequences,
// /floor), bytes 2 and 3 the new link's name and its target:
//   a soft link, an external link, a user-defined link, a second hard link
//   to an object (anywhere), a dataset with external storage, a virtual
//   dataset (in /sequences, which the reader reads whole).
// Then the reader opens the image. Properties (a failure aborts): a file
// with an edit is refused with the reader's one-line refusal of links or
// foreign storage (never opened elsewhere: the link targets name files
// that do not exist, so following one would end in another error); the
// file without edits opens and its frames read.
#include <H5Cpp.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "data/h5_util.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "support/dataset_image.hpp"

namespace {

constexpr std::size_t kMaxEdits = 8;
constexpr H5L_type_t kUserLink = H5L_type_t(100);  // a user-defined link class of this harness

const std::string& good_image() {
  static const std::string bytes = [] {
    std::ifstream in(PTNET_FUZZ_GOOD_DATASET, std::ios::binary);
    std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (s.empty()) std::abort();
    return s;
  }();
  return bytes;
}

// A user-defined link class whose traversal always fails.
hid_t refuse_traversal(const char*, hid_t, const void*, std::size_t, hid_t, hid_t) { return -1; }

void register_user_link() {
  static const bool done = [] {
    static const H5L_class_t cls = {H5L_LINK_CLASS_T_VERS, kUserLink, "ptnet fuzz link", nullptr, nullptr,
                                    nullptr, refuse_traversal, nullptr, nullptr};
    return H5Lregister(&cls) >= 0;
  }();
  (void)done;
}

// The file image of `bytes` edited by `edits`, and whether an edit took.
std::string edited(const std::uint8_t* data, std::size_t edits, bool& changed) {
  const std::string& image = good_image();
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_core(fapl, 1 << 16, /*backing_store=*/0);
  H5Pset_file_image(fapl, const_cast<char*>(image.data()), image.size());
  const hid_t file = H5Fopen("fuzz.h5", H5F_ACC_RDWR, fapl);
  H5Pclose(fapl);
  if (file < 0) std::abort();
  const hid_t floor = H5Gcreate2(file, "floor", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (floor >= 0) H5Gclose(floor);
  static const char* const kWhere[] = {"", "sequences/", "floor/"};
  static const char* const kSoft[] = {"/sequences/walk__b1", "/bodies", "/", "/missing", "/sequences", "x"};
  static const char* const kFiles[] = {"ptnet-fuzz-missing.h5", "fuzz.h5", "/nonexistent/ptnet.h5"};
  changed = false;
  for (std::size_t i = 0; i < edits; ++i) {
    const std::uint8_t* e = data + 4 * i;
    char name[48];
    std::snprintf(name, sizeof name, "%sl%02x", kWhere[e[1] % 3], e[2]);
    const char* soft = kSoft[e[3] % 6];
    herr_t rc = -1;
    switch (e[0] % 7) {
      case 0:
        continue;
      case 1:
        rc = H5Lcreate_soft(soft, file, name, H5P_DEFAULT, H5P_DEFAULT);
        break;
      case 2:
        rc = H5Lcreate_external(kFiles[e[3] % 3], soft, file, name, H5P_DEFAULT, H5P_DEFAULT);
        break;
      case 3:
        register_user_link();
        rc = H5Lcreate_ud(file, name, kUserLink, soft, std::strlen(soft), H5P_DEFAULT, H5P_DEFAULT);
        break;
      case 4:
        rc = H5Lcreate_hard(file, e[3] % 2 ? "/sequences/walk__b1" : "/", file, name, H5P_DEFAULT, H5P_DEFAULT);
        break;
      case 5:
      case 6: {
        std::snprintf(name, sizeof name, "sequences/l%02x", e[2]);
        hsize_t dims[3] = {3, 4, 2};
        const hid_t space = H5Screate_simple(3, dims, nullptr);
        const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
        if (e[0] % 7 == 5) {
          H5Pset_external(dcpl, kFiles[e[3] % 3], 0, 3 * 4 * 2 * 4);
        } else {
          const hid_t source = H5Screate_simple(3, dims, nullptr);
          H5Pset_virtual(dcpl, space, kFiles[e[3] % 3], "/frames", source);
          H5Sclose(source);
        }
        const hid_t ds = H5Dcreate2(file, name, H5T_IEEE_F32LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
        rc = ds;
        if (ds >= 0) H5Dclose(ds);
        H5Pclose(dcpl);
        H5Sclose(space);
        break;
      }
    }
    changed = changed || rc >= 0;
  }
  H5Fflush(file, H5F_SCOPE_GLOBAL);
  const ssize_t size = H5Fget_file_image(file, nullptr, 0);
  std::string out(std::size_t(size > 0 ? size : 0), '\0');
  if (size <= 0 || H5Fget_file_image(file, out.data(), out.size()) != size) std::abort();
  H5Fclose(file);
  return out;
}

bool is_refusal(const std::string& message) {
  for (const char* what : {" is a soft link", " is an external link", " is a user-defined link",
                           " is a second name of ", " is a virtual dataset", " keeps its data in the external file"})
    if (message.find(what) != std::string::npos) return message.rfind("fuzz.h5: ", 0) == 0;
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ptnet::h5::quiet();
  const std::size_t edits = std::min(size / 4, kMaxEdits);
  bool changed = false;
  const std::string image = edited(data, edits, changed);
  try {
    const ptnet::Dataset d = ptnet::open_dataset_image(image, "fuzz.h5");
    if (changed) {
      // Only what the reader never looks at may stay: none of the edits is.
      std::fprintf(stderr, "fuzz_dataset_links: a file with %zu edits was accepted\n", edits);
      std::abort();
    }
    for (const auto& m : d.sequences()) (void)d.read(m.name);
  } catch (const ptnet::Error& e) {
    if (!changed || !is_refusal(e.what())) {
      std::fprintf(stderr, "fuzz_dataset_links: %s\n", e.what());
      std::abort();
    }
  }
  return 0;
}
