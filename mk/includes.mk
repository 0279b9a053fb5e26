# make check-includes: the folder-level include graph of include/rt and src (a folder ->
# the folders whose rt/ headers its files include), which fails on any cycle of folders
# (tests/tools/include_graph.py; docs/design.md, "Folders").
.PHONY: check-includes
check-includes:
	python3 tests/tools/include_graph.py

test: check-includes
