// hairsim <command> [options]: the commands and their options are in CliApp.cs and each command's file (RunCommand.cs, …).
return HairSim.Cli.CliApp.Run(args);
