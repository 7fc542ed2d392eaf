// Poisson_remesh's own named parameters, listed once: parameters.h turns each line into a tag
// type, a member function of Poisson_remesh::Named_function_parameters and a free function of
// Poisson_remesh::parameters. No include guard on purpose (included several times with a macro).
//
// POISSON_REMESH_add_named_parameter(tag type, tag value, function name)

// target size of the output (sampler and remesher)
POISSON_REMESH_add_named_parameter(target_vertex_count_t, target_vertex_count, target_vertex_count)
POISSON_REMESH_add_named_parameter(target_edge_length_t, target_edge_length, target_edge_length)
POISSON_REMESH_add_named_parameter(sampling_radius_t, sampling_radius, sampling_radius)

// density and features
POISSON_REMESH_add_named_parameter(density_t, density, density)
POISSON_REMESH_add_named_parameter(feature_policy_t, feature_policy, feature_policy)
POISSON_REMESH_add_named_parameter(sharp_angle_t, sharp_angle, sharp_angle)
POISSON_REMESH_add_named_parameter(corner_angle_t, corner_angle, corner_angle)
POISSON_REMESH_add_named_parameter(minimum_feature_length_t, minimum_feature_length, minimum_feature_length)

// the pluggable models of the package's concepts
POISSON_REMESH_add_named_parameter(geodesic_oracle_t, geodesic_oracle, geodesic_oracle)
POISSON_REMESH_add_named_parameter(sampler_t, sampler, sampler)
POISSON_REMESH_add_named_parameter(relaxer_t, relaxer, relaxer)

// remesher: the largest deviation from the input mended by inserted input vertices
POISSON_REMESH_add_named_parameter(fidelity_tolerance_t, fidelity_tolerance, fidelity_tolerance)
// remesher: finer sampling around pointed tips, graded back to the spacing
POISSON_REMESH_add_named_parameter(feature_grading_t, feature_grading, feature_grading)
// remesher: remeshes made again, finer where the last one crossed itself or kept sharp triangles
POISSON_REMESH_add_named_parameter(regrading_attempts_t, regrading_attempts, regrading_attempts)
// remesher: a remake redoes only the regions at fault (false: the whole remesh)
POISSON_REMESH_add_named_parameter(local_remakes_t, local_remakes, local_remakes)
POISSON_REMESH_add_named_parameter(relaxation_settings_t, relaxation_settings, relaxation_settings)

// input reading and validation
POISSON_REMESH_add_named_parameter(repair_degenerate_faces_t, repair_degenerate_faces, repair_degenerate_faces)
POISSON_REMESH_add_named_parameter(repair_non_manifold_vertices_t, repair_non_manifold_vertices, repair_non_manifold_vertices)
POISSON_REMESH_add_named_parameter(strict_input_t, strict_input, strict_input)

// long runs: progress reports and cancellation (progress.h; CGAL's `callback` is read too)
POISSON_REMESH_add_named_parameter(progress_t, progress, progress)

// quality report
POISSON_REMESH_add_named_parameter(check_self_intersections_t, check_self_intersections, check_self_intersections)
POISSON_REMESH_add_named_parameter(angle_histogram_bin_width_t, angle_histogram_bin_width, angle_histogram_bin_width)
POISSON_REMESH_add_named_parameter(hausdorff_relative_error_bound_t, hausdorff_relative_error_bound, hausdorff_relative_error_bound)
POISSON_REMESH_add_named_parameter(sampled_hausdorff_t, sampled_hausdorff, sampled_hausdorff)
POISSON_REMESH_add_named_parameter(reference_self_intersections_t, reference_self_intersections, reference_self_intersections)
