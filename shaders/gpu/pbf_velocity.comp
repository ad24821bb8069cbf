// PBF, Algorithm 1 line 21: v_i += (x_i - x*_i)/dt (the prediction already moved x by v dt), the
// equivalent pressure p_i = -rho_i^2 (sum(lambda_i) + N q_i)/(rho0 dt^2) for the statistics
// (N iterations, q_i s_corr's share from pbf_lambda.comp), and the safety net (put-back, counted).
BUFFER_POS BUFFER_VEL BUFFER_DENS BUFFER_PRED BUFFER_LAMBDA BUFFER_WGRAD
layout(std430, binding = RTSPH_B_REDUCE) buffer Counter { uint put_back_count; };
uniform float inv_dt;
uniform double pressure_scale;  // -1/(rho0 dt^2)
uniform float iterations;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 x = pos[i].xyz;
  vec3 v = vel[i].xyz + (x - pred[i].xyz) * inv_dt;
  float rho = dens[i].x;
  dens[i].y = float(pressure_scale * double(rho) * double(rho) *
                    (double(lam[i].y) + double(iterations) * double(wgrad[i].w)));
  if (put_back(x, v)) atomicAdd(put_back_count, 1u);
  pos[i] = vec4(x, 0.0);
  vel[i] = vec4(v, 0.0);
}
