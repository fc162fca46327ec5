//! Stiff and extreme scenes, parametrised and seeded (issue 15): see [`generate`].
