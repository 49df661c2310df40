// Reduction of volume 0 alone over the lattice steps of [tEnter, tExit], into its layer state
  // (x: max, min or sum; y: averaged length; z: the layer's depth t; w: 1 once the ray met the
  // volume), carried across fragments through the layer buffer read back in gState. Every
  // step counts (no early termination); skipping probes at every step.
  float kk = floor(tEnter / dt - phase);
  vec4 state = gState;
  //STRATA::Start::Impl
  for (int it = 0; it < 1048576; ++it)
  {
    float a = max((kk + phase) * dt, tEnter);
    float b = min((kk + 1.0 + phase) * dt, tExit);
    if (a >= tExit)
    {
      break;
    }
    //STRATA::Skip::Impl
    if (b > a)
    {
      float t = 0.5 * (a + b);
      float s = strataScalar0(o + t * d);
      //STRATA::Reduce::Impl
    }
    kk += 1.0;
  }
  acc = state;
