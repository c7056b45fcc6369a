// beam_two_cells.geo — the beam of beam.geo two cells thick (ny = 2), for the
// redistributed mass, which needs vertices off the contact side that are not all on
// one line (kernel/cdyn/mass_redistribution.hpp): cdyn run data/scenes/beam.toml
// --set mesh.file=data/geo/beam_two_cells.geo
ny = 2;
Include "beam.geo";
