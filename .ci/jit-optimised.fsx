// Exit 1 if the assembly given as the first argument was built with the JIT optimiser disabled (DebuggableAttribute).
let path = fsi.CommandLineArgs.[1]
let asm = System.Reflection.Assembly.LoadFrom path
let disabled =
    asm.GetCustomAttributes(typeof<System.Diagnostics.DebuggableAttribute>, false)
    |> Array.exists (fun a -> (a :?> System.Diagnostics.DebuggableAttribute).IsJITOptimizerDisabled)
printfn "%s: JIT optimiser %s" (System.IO.Path.GetFileName path) (if disabled then "DISABLED" else "on")
exit (if disabled then 1 else 0)
