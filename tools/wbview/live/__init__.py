"""The live pages (docs/live.md): a lab's own C++ compiled to WebAssembly, in a page."""
