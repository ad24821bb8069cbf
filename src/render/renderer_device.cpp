// The GPU backend's fluid drawn from its own buffers: the particle shaders' eight scalar
// attributes (x, y, z, vx, vy, vz, ρ, p) point into the simulation's vec4 arrays with a 16-byte
// stride, so nothing is copied or read back per frame (issue 10, §3). Both share the context.
#include "render/renderer.h"

namespace rtsph::render {

void Renderer::use_device(const DeviceParticles& f, const BoundaryView* b) {
  if (!have_domain_) dim_ = f.dim;
  fluid_n_ = f.count;
  fluid_box_ = false;  // the positions stay on the GPU: the surface passes cover the frame
  positions_.clear();
  max_speed_ = f.max_speed;
  p_min_ = f.pressure_min;
  p_max_ = f.pressure_max;
  rho_min_ = f.density_min;
  rho_max_ = f.density_max;
  struct Source { GLuint buffer; int offset; bool present; };
  const Source attrs[8] = {{f.position, 0, true},  {f.position, 4, true},  {f.position, 8, f.dim == 3},
                           {f.velocity, 0, true},  {f.velocity, 4, true},  {f.velocity, 8, f.dim == 3},
                           {f.density, 0, true},   {f.density, 4, true}};
  glBindVertexArray(fluid_vao_);
  for (GLuint i = 0; i < 8; ++i) {
    if (attrs[i].present && attrs[i].buffer && f.count > 0) {
      glBindBuffer(GL_ARRAY_BUFFER, attrs[i].buffer);
      glVertexAttribPointer(i, 1, GL_FLOAT, GL_FALSE, 16, reinterpret_cast<void*>(std::intptr_t(attrs[i].offset)));
      glVertexAttribDivisor(i, 1);
      glEnableVertexAttribArray(i);
    } else {
      glDisableVertexAttribArray(i);
    }
  }
  // The compute passes wrote these buffers; vertex fetch must see it.
  glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
  upload_boundary(b);
}

}  // namespace rtsph::render
