# Doxygen input filter of the user manual (FILTER_PATTERNS in doc/Doxyfile.in). The manual's links
# are relative to its place in the repository, as GitHub shows it; in the HTML reference the
# pictures (IMAGE_PATH) are copied next to the pages, and the concept pages are classes, which
# Doxygen links by name. Line numbers are kept.
s#](\.\./\.\./benchmark/Poisson_remesh/\([^)]*\.png\))#](\1)#g
s#\[\(`[A-Za-z]*`\)\](Concepts/[A-Za-z]*\.h)#\1#g
