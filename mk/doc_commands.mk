# make check-doc-commands: the animation commands of docs/animations.md and of the README's
# step 4 (Animate) run as written over their first frames (tests/doc_commands.sh; needs
# ../shared and GNU parallel; about 10 s).
.PHONY: check-doc-commands
check-doc-commands: raytracer
	tests/doc_commands.sh
