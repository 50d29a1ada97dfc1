-- expect: safe_binary_chunk\.lua:6: attempt to load a binary chunk \(mode is 't'\)
-- case: permission | --safe: a deck loads a binary (precompiled) chunk, which can crash the interpreter
-- options: --safe
-- status: 1
local bytecode = string.dump(function() return 1 end)
local chunk = assert(load(bytecode, "=bytecode", "b"))
error("the binary chunk was loaded")
