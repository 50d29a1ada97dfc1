-- expect: unknown option '--ouptut=elsewhere' \(did you mean '--output'\?\) \(see moraine --help\)
-- case: other | a misspelt long option on the command line
-- options: --ouptut=elsewhere
-- status: 2
print("never run: the command line is refused first")
