//! Procedural meshes like the labs' (seed 004's plane, star, text and torus).
