// TetGen 1.5.0's terminatetetgen() (tetgen.h, where it is an inline function) frees the
// mesh (tetgenmesh::freememory) and then throws the error code; while the exception
// unwinds, the tetgenmesh on tetrahedralize()'s stack frees the same pools again in its
// destructor. That double free aborts the process ("free(): invalid pointer") and the
// error code is lost. libtet calls terminatetetgen through its procedure linkage table,
// so this definition, in the program, is the one it calls: it only throws, and the
// destructor frees the mesh once. In a file of its own because tetgen.h defines the
// inline version.
class tetgenmesh;

void terminatetetgen(tetgenmesh* /*mesh*/, int code) {
  throw code;
}

namespace mixmesh::farfield_detail {

// Referenced from tetgen_call.cpp, so the linker takes this file from the static library.
void use_single_free_termination() {}

}  // namespace mixmesh::farfield_detail
