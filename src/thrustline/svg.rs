//! SVG drawings of assemblies, thrust lines and mechanisms (plotters, SVG backend).
