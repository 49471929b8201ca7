// Two plates with closed forms, for the commands that read a scene: a 1 x 1 emitter (E = 2, 1, 0.5;
// black) in the plane y = 0 facing +y, and a 1 x 1 receiver (rho = 0.5) 1 above it facing down:
// Howell C-11 between them, B-3 to points. Also two probe points: the receiver's centre (on it:
// radiosity too) and a point in space under its corner.
#pragma once

#include "../support/temp_dir.h"

namespace hrad::test {

inline void write_plates(const TempDir& dir) {
  dir.write("plates.mtl", "newmtl light\nKd 0 0 0\nKe 2 1 0.5\nnewmtl white\nKd 0.5 0.5 0.5\n");
  dir.write("plates.obj",
            "mtllib plates.mtl\no light\nusemtl light\nv 0 0 0\nv 0 0 1\nv 1 0 1\nv 1 0 0\nf 1 2 3 4\n"
            "o receiver\nusemtl white\nv 0 1 0\nv 1 1 0\nv 1 1 1\nv 0 1 1\nf 5 6 7 8\n");
  dir.write("points.csv", "x,y,z,nx,ny,nz\n0.5,1,0.5,0,-1,0\n0,0.5,0,0,-1,0\n");
}

}  // namespace hrad::test
