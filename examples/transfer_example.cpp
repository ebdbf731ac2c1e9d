// transfer_example: use the ptnet library from another program.
//
//   build-examples/transfer_example model/ walk.npy out.npy
//
// Built against the installed package (examples/CMakeLists.txt:
// find_package(ptnet), ptnet::ptnet).
//
// Loads a trained model folder, reads a recorded [T, 80, 28] float32 kPa
// sequence of a 165 cm / 60 kg woman, transfers it to a 185 cm / 95 kg man
// and prints the total vertical force per second of both.
#include <cstdio>
#include <exception>

#include "ptnet/npy.hpp"
#include "ptnet/transfer.hpp"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s MODEL_DIR IN.npy OUT.npy\n", argv[0]);
    return 2;
  }
  try {
    ptnet::Transfer net(argv[1]);  // config.json + model.pt, validated
    const ptnet::ModelDir& m = net.model();
    ptnet::PressureSequence in = ptnet::read_npy_sequence(argv[2], m.mat, m.fps);
    ptnet::BodySpec source{"recorded", ptnet::Sex::female, 165, 60};
    ptnet::BodySpec target{"wanted", ptnet::Sex::male, 185, 95};
    ptnet::PressureSequence out = net.run(in, source, target);
    ptnet::write_npy_sequence(argv[3], out, /*force=*/false);

    // Total force (N) = sum of kPa x cell area x 1000, averaged per second.
    const double area_m2 = m.mat.cell_area_m2();
    const int per_s = int(m.fps);
    for (int t0 = 0; t0 + per_s <= in.frames(); t0 += per_s) {
      double f_in = 0, f_out = 0;
      for (int t = t0; t < t0 + per_s; ++t)
        for (int c = 0; c < m.mat.cells(); ++c) {
          f_in += in.frame(t)[c] * area_m2 * 1000.0 / per_s;
          f_out += out.frame(t)[c] * area_m2 * 1000.0 / per_s;
        }
      std::printf("second %3d: recorded %7.1f N  transferred %7.1f N\n", t0 / per_s, f_in, f_out);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "transfer_example: error: %s\n", e.what());
    return 1;
  }
}
