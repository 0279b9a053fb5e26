# make format        rewrite every C++ file of the tree in the style of .clang-format
# make format-check  list the files that differ from that style and fail if any does (CI runs it)
# Both need clang-format (Debian: apt-get install clang-format).
CLANG_FORMAT ?= clang-format
FORMAT_FILES  = $(shell git ls-files '*.cpp' '*.h' 2>/dev/null || find src include tests -name '*.cpp' -o -name '*.h')

.PHONY: format format-check
format:
	@command -v $(CLANG_FORMAT) >/dev/null || { echo "make format: $(CLANG_FORMAT) not found (apt-get install clang-format)"; exit 1; }
	$(CLANG_FORMAT) -i $(FORMAT_FILES)

format-check:
	@command -v $(CLANG_FORMAT) >/dev/null || { echo "make format-check: $(CLANG_FORMAT) not found (apt-get install clang-format)"; exit 1; }
	@bad=$$(for f in $(FORMAT_FILES); do $(CLANG_FORMAT) --dry-run --Werror "$$f" >/dev/null 2>&1 || echo "$$f"; done); \
	if [ -n "$$bad" ]; then echo "make format-check: not in the style of .clang-format (make format fixes them):"; echo "$$bad"; exit 1; \
	else echo "make format-check: $(words $(FORMAT_FILES)) files in the style of .clang-format"; fi
